#include "scene/canonical_scenes.h"

#include <cmath>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "penumbra/scene_builder.h"
#include "scene/canonical_scene_parts.h"

namespace penumbra {
namespace {

using namespace canonical;

// Casters at 2, 10, 40, 90 and 140 m: every cascade (and the distance fade) sees one. Each distance has
// a cube, a pole beside it and, from 40 m on, a wall behind it facing the camera, so that far shadows
// land on a surface the camera sees head-on rather than on the foreshortened ground.
Scene makeNearFarCasters() {
    SceneBuilder builder;
    addGround(builder, 600.0f, -250.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t white = builder.addMaterial(colored("backdrop", glm::vec3(0.85f)));
    const float distances[5] = {2.0f, 10.0f, 40.0f, 90.0f, 140.0f};
    const float bearings[5] = {12.0f, -20.0f, 18.0f, -10.0f, 6.0f};  // degrees right of the view axis
    for (int i = 0; i < 5; ++i) {
        const float d = distances[i], size = std::max(0.4f, 0.07f * d);
        const float x = d * std::tan(glm::radians(bearings[i]));
        const std::string tag = std::to_string(int(d)) + "m";
        addBox(builder, glm::vec3(0.5f * size), red, at({x, 0.5f * size, -d}), "cube_" + tag);
        addPole(builder, std::max(0.04f, 0.01f * d), 2.0f * size + 0.5f, red, {x + 1.5f * size, 0, -d}, "pole_" + tag);
        if (d >= 40.0f)
            addBox(builder, {3.0f * size, 1.5f * size, 0.15f}, white, at({x, 1.5f * size, -d - 1.0f * size}),
                   "wall_" + tag);
    }
    // A 4 x 3 m table top 1.2 m up at 5.5-8.5 m: a large shadow in the first cascades, lit ground around.
    addBox(builder, {2.0f, 0.05f, 1.5f}, white, at({-2.5f, 1.2f, -7.0f}), "table_7m");
    builder.addLight(sunFrom(40.0f, 35.0f));
    setCamera(builder, {0.0f, 1.6f, 0.0f}, {0.0f, 0.2f, -5.4f}, 60.0f);
    return builder.build();
}

// A 10 cm wall and a 2 cm panel standing on the floor with the sun behind them: the floor in their
// shadow touches their base, where too much bias lets light leak under them (peter-panning).
Scene makeThinWall() {
    SceneBuilder builder;
    addGround(builder, 60.0f);
    const uint32_t white = builder.addMaterial(colored("wall", glm::vec3(0.85f)));
    addBox(builder, {3.0f, 1.25f, 0.05f}, white, at({0.0f, 1.25f, -6.0f}), "wall_10cm");
    addBox(builder, {1.5f, 1.0f, 0.01f}, white, rotated(at({4.5f, 1.0f, -4.0f}), 30.0f, {0, 1, 0}), "panel_2cm");
    addBox(builder, {0.05f, 0.6f, 1.5f}, white, at({-4.5f, 0.6f, -3.5f}), "fin_10cm");
    builder.addLight(sunFrom(35.0f, 160.0f));
    setCamera(builder, {2.0f, 3.0f, 4.0f}, {0.5f, 0.3f, -5.0f}, 55.0f);
    return builder.build();
}

// Poles of 3 to 20 cm radius between 3 and 30 m and a thin rail: shadows one or two texels wide.
Scene makePoles() {
    SceneBuilder builder;
    addGround(builder, 100.0f, -20.0f);
    const uint32_t gray = builder.addMaterial(colored("pole", {0.4f, 0.4f, 0.45f}));
    const float radii[6] = {0.03f, 0.05f, 0.1f, 0.05f, 0.2f, 0.1f};
    const glm::vec2 bases[6] = {{-1.5f, -3.0f}, {1.0f, -5.0f}, {-3.0f, -9.0f}, {3.5f, -14.0f}, {-5.0f, -22.0f},
                                {6.0f, -30.0f}};
    for (int i = 0; i < 6; ++i)
        addPole(builder, radii[i], 3.0f + float(i), gray, {bases[i].x, 0.0f, bases[i].y}, "pole_" + std::to_string(i));
    for (int row = 0; row < 3; ++row)  // a grove: 3 x 4 poles of 8 cm radius at 10-20 m
        for (int column = 0; column < 4; ++column)
            addPole(builder, 0.08f, 5.0f, gray, {-8.0f + 1.5f * float(column) + 0.5f * float(row), 0.0f,
                                                 -10.0f - 4.0f * float(row)},
                    "grove_" + std::to_string(row) + "_" + std::to_string(column));
    addPole(builder, 0.05f, 2.0f, gray, {-2.0f, 0.0f, -6.0f}, "rail_post_left");
    addPole(builder, 0.05f, 2.0f, gray, {2.0f, 0.0f, -6.0f}, "rail_post_right");
    addBox(builder, {2.0f, 0.03f, 0.03f}, gray, at({0.0f, 1.8f, -6.0f}), "rail");
    builder.addLight(sunFrom(35.0f, 60.0f));
    setCamera(builder, {0.0f, 2.0f, 2.0f}, {0.0f, 0.5f, -10.0f}, 60.0f);
    return builder.build();
}

// Receivers nearly edge-on to the sun, where shadow acne starts: two ramps whose normals are 70° and 80°
// from the sun direction (N·L 0.34 and 0.17) and a wall at 80°, each with a caster above it.
Scene makeGrazing() {
    SceneBuilder builder;
    addGround(builder, 60.0f);
    const uint32_t white = builder.addMaterial(colored("receiver", glm::vec3(0.85f)));
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    // Sun from +X at 50° elevation; a ramp tilted by t about Z has normal (-sin t, cos t, 0), at 50° + t
    // from the direction to the sun.
    const float tilts[2] = {20.0f, 30.0f};
    const float xs[2] = {4.0f, -4.0f};
    for (int i = 0; i < 2; ++i) {
        const glm::mat4 pose = rotated(at({xs[i], 2.2f, -4.0f}), tilts[i], {0, 0, 1});
        const std::string tag = std::to_string(int(50.0f + tilts[i])) + "deg";
        addBox(builder, {3.0f, 0.05f, 3.0f}, white, pose, "ramp_" + tag);
        addBox(builder, glm::vec3(0.3f), red, pose * at({1.5f, 0.8f, 0.0f}), "cube_over_ramp_" + tag);
    }
    // A wall turned 15.7° about Y: its normal (sin b, 0, cos b) makes N·L = cos 50° sin b = cos 80°.
    const float wallTurn = glm::degrees(std::asin(std::cos(glm::radians(80.0f)) / std::cos(glm::radians(50.0f))));
    addBox(builder, {3.0f, 1.5f, 0.1f}, white, rotated(at({0.0f, 1.5f, -12.0f}), wallTurn, {0, 1, 0}), "wall_80deg");
    addBox(builder, glm::vec3(0.3f), red, at({2.0f, 4.5f, -11.6f}), "cube_over_wall");
    builder.addLight(sunFrom(50.0f, 90.0f));
    setCamera(builder, {-1.0f, 9.0f, 7.0f}, {0.0f, 1.0f, -6.0f}, 60.0f);
    return builder.build();
}

// A leaf: an opaque ellipse with a grid of round holes, transparent around it (alpha 0 or 255).
Texture makeLeafTexture() {
    constexpr int kSize = 64, kCell = 16;
    Texture texture;
    texture.name = "leaf";
    texture.rgba = Image(kSize, kSize, 4);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float u = (float(x) + 0.5f) / kSize - 0.5f, v = (float(y) + 0.5f) / kSize - 0.5f;
            const bool inLeaf = (u * u) / (0.48f * 0.48f) + (v * v) / (0.4f * 0.4f) < 1.0f;
            const float cx = float(x % kCell) + 0.5f - 0.5f * kCell, cy = float(y % kCell) + 0.5f - 0.5f * kCell;
            const bool hole = cx * cx + cy * cy < 0.3f * kCell * 0.3f * kCell;
            texture.rgba.at(x, y, 0) = 60;
            texture.rgba.at(x, y, 1) = 150;
            texture.rgba.at(x, y, 2) = 40;
            texture.rgba.at(x, y, 3) = inLeaf && !hole ? 255 : 0;
        }
    return texture;
}

// Alpha-masked (MASK, cutoff 0.5) double-sided quads: upright, tilted and a canopy; their shadows
// must have the holes of the texture (material shadows: clip).
Scene makeFoliage() {
    SceneBuilder builder;
    addGround(builder, 40.0f);
    Material leaf = colored("leaf_mask", glm::vec3(1.0f));
    leaf.baseColorTexture = int(builder.addTexture(makeLeafTexture()));
    leaf.alphaMode = AlphaMode::Mask;
    leaf.alphaCutoff = 0.5f;
    leaf.doubleSided = true;
    leaf.shadows = MaterialShadowMode::Clip;
    const uint32_t quad = builder.addMesh(makeQuadMesh({3.0f, 3.0f}, builder.addMaterial(leaf)));
    const glm::vec3 positions[5] = {{-3.5f, 1.7f, -3.0f}, {0.0f, 2.0f, -4.5f}, {3.5f, 1.6f, -3.5f},
                                    {-2.0f, 2.2f, -8.0f}, {3.0f, 2.4f, -9.0f}};
    const float turns[5] = {20.0f, -35.0f, 60.0f, 10.0f, -15.0f};
    const float tilts[5] = {0.0f, 15.0f, -20.0f, 30.0f, 0.0f};
    for (int i = 0; i < 5; ++i) {
        const glm::mat4 pose = rotated(rotated(at(positions[i]), turns[i], {0, 1, 0}), tilts[i], {1, 0, 0});
        builder.addInstance(quad, pose, true, "leaf_" + std::to_string(i));
    }
    const glm::mat4 canopy = glm::scale(rotated(rotated(at({0.5f, 3.8f, -6.0f}), -80.0f, {1, 0, 0}), 20.0f, {0, 0, 1}),
                                        glm::vec3(1.5f, 1.5f, 1.0f));
    builder.addInstance(quad, canopy, true, "leaf_canopy");
    builder.addLight(sunFrom(55.0f, 30.0f));
    setCamera(builder, {0.0f, 4.0f, 5.0f}, {0.0f, 0.5f, -4.5f}, 55.0f);
    return builder.build();
}

// The sun 8° above the horizon: shadows seven times longer than their casters, the ground at N·L 0.14.
Scene makeLowSun() {
    SceneBuilder builder;
    addGround(builder, 300.0f, -60.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    addBox(builder, glm::vec3(0.4f), red, at({1.0f, 0.4f, -4.0f}), "cube_4m");
    addBox(builder, {1.0f, 1.5f, 1.0f}, red, at({-3.0f, 1.5f, -15.0f}), "block_15m");
    addBox(builder, {4.0f, 1.0f, 0.1f}, red, at({4.0f, 1.0f, -28.0f}), "wall_28m");
    addPole(builder, 0.1f, 3.0f, red, {-1.0f, 0.0f, -8.0f}, "pole_8m");
    addPole(builder, 0.3f, 8.0f, red, {6.0f, 0.0f, -45.0f}, "pole_45m");
    builder.addLight(sunFrom(8.0f, 60.0f));
    setCamera(builder, {0.0f, 3.0f, 4.0f}, {0.0f, 0.0f, -15.0f}, 60.0f);
    return builder.build();
}

void addRoomObjects(SceneBuilder& builder) {
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    addBox(builder, glm::vec3(0.5f), red, at({-1.5f, 0.5f, -4.0f}), "cube");
    addBox(builder, {0.4f, 1.2f, 0.4f}, blue, at({2.0f, 1.2f, -6.0f}), "block");
    addBox(builder, {2.5f, 1.5f, 0.1f}, red, at({0.0f, 1.5f, -9.5f}), "wall");
    addPole(builder, 0.08f, 2.5f, blue, {0.5f, 0.0f, -3.0f}, "pole");
    addSphere(builder, 0.6f, blue, {-2.5f, 0.6f, -7.0f}, "sphere");
}

// Two shadowed spot lights over boxes, a pole, a sphere and a wall; the second with hard shadows.
Scene makeSpotLightsScene() {
    SceneBuilder builder;
    addGround(builder, 30.0f);
    addRoomObjects(builder);
    const glm::vec3 wsLeft(-3.0f, 5.0f, -2.0f), wsRight(4.0f, 4.0f, -3.0f);
    Light left = makeSpotLight(wsLeft, glm::vec3(-1.0f, 0.0f, -5.0f) - wsLeft, 60.0f, 20.0f, glm::radians(40.0f),
                               glm::radians(30.0f));
    left.name = "spot_soft";
    left.shadows = LightShadows::Soft;
    builder.addLight(left);
    Light right = makeSpotLight(wsRight, glm::vec3(1.5f, 0.0f, -7.0f) - wsRight, 60.0f, 20.0f, glm::radians(35.0f),
                                glm::radians(25.0f));
    right.name = "spot_hard";
    right.shadows = LightShadows::Hard;
    builder.addLight(right);
    setCamera(builder, {0.0f, 5.0f, 4.0f}, {0.0f, 0.5f, -5.0f}, 60.0f);
    return builder.build();
}

// One shadowed point light among the same objects: shadows fall in every direction (all six faces).
Scene makePointLightScene() {
    SceneBuilder builder;
    addGround(builder, 30.0f);
    addRoomObjects(builder);
    Light bulb = makePointLight({0.0f, 2.5f, -5.5f}, 40.0f, 15.0f);
    bulb.name = "point";
    bulb.shadows = LightShadows::Soft;
    builder.addLight(bulb);
    setCamera(builder, {0.0f, 6.0f, 3.0f}, {0.0f, 0.0f, -5.5f}, 60.0f);
    return builder.build();
}

struct Entry {
    CanonicalSceneInfo info;
    std::function<Scene()> make;
};

const std::vector<Entry>& entries() {
    static const std::vector<Entry> kEntries = {
        {{"near_far_casters", "cubes, poles and walls at 2, 10, 40, 90 and 140 m under a 40° sun"}, makeNearFarCasters},
        {{"thin_wall", "10 cm wall, 2 cm panel and a fin on a floor, sun behind them (leaks, peter-panning)"},
         makeThinWall},
        {{"poles", "poles of 3-20 cm radius from 3 to 30 m and a thin rail (thin shadows)"}, makePoles},
        {{"grazing", "ramps and a wall at 70° and 80° to the sun (acne)"}, makeGrazing},
        {{"foliage", "alpha-masked double-sided leaf quads with holes (clipped shadows)"}, makeFoliage},
        {{"low_sun", "sun at 8° elevation: long shadows over a grazing ground"}, makeLowSun},
        {{"spot_lights", "two shadowed spot lights (soft and hard)"}, makeSpotLightsScene},
        {{"point_light", "one shadowed point light among boxes"}, makePointLightScene},
        {{"far_field", "boxes and spheres from 3 to 145 m under a 40° sun, every cascade (maxDistance 150)"},
         makeFarField},
        {{"thin_slabs", "2 and 5 cm walls, 2-5 cm poles, a 1 cm slab 2 cm above the floor"}, makeThinSlabs},
        {{"grazing_sun", "sun at 10°: slabs tilted 4-16° on a floor, spheres and a cylinder (terminators)"},
         makeGrazingSun},
        {{"fence", "alpha-masked picket fence and leaf cards, NEAREST-sampled textures"}, makeFence},
        {{"field_of_objects", "576 small boxes, spheres and poles over 70 m x 100 m"}, makeFieldOfObjects},
        {{"cube", "a 2 m cube on a plane under a 45° sun"}, makeCube},
        {{"cad_engine", "the 2CylinderEngine CAD model (121k triangles, cracks): light 0 a 35° sun, light 1 a spot",
          true},
         makeCadEngine},
        {{"spot_shelf", "three spot lights (two soft, one hard) over a box, a ball, a pole and a wall shelf"},
         makeSpotShelf},
        {{"pcss_contact", "contact-hardening soft shadows: a 3° pcss sun (light 0) and a pcss spot with a 15 cm emitter"},
         makePcssContact},
        {{"room_corner", "a point light 2.5 m up, 1 m from both walls of a room corner: shadows on five cube faces"},
         makeRoomCorner},
    };
    return kEntries;
}

}  // namespace

const std::vector<CanonicalSceneInfo>& canonicalScenes() {
    static const std::vector<CanonicalSceneInfo> kInfos = [] {
        std::vector<CanonicalSceneInfo> infos;
        for (const Entry& entry : entries()) infos.push_back(entry.info);
        return infos;
    }();
    return kInfos;
}

std::string canonicalSceneFileName(const std::string& name) {
    for (const Entry& entry : entries())
        if (entry.info.name == name) return entry.info.fileName();
    return name + ".gltf";
}

Scene makeCanonicalScene(const std::string& name) {
    for (const Entry& entry : entries())
        if (entry.info.name == name) return entry.make();
    throw Error("unknown canonical scene '" + name + "'");
}

}  // namespace penumbra
