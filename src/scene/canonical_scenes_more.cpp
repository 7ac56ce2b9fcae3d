// The canonical scenes added for the shadow-fidelity measurements (docs/fidelity.md): one per scene type of
// its measurement table that the first eight did not cover (far field, thin slabs, grazing sun,
// NEAREST-sampled fence and cards, a field of small objects, a single cube, a CAD model under a sun and a
// spot, three spots on a shelf).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/canonical_scene_parts.h"
#include "scene/canonical_scenes.h"
#include "scene/gltf_loader.h"

namespace penumbra::canonical {

// Boxes and spheres from 3 to 145 m: every cascade of a 150 m shadow distance holds some, and the far
// ones stand before walls facing the camera. The far-field shimmer scene (use --set shadows.maxDistance=150).
Scene makeFarField() {
    SceneBuilder builder;
    addGround(builder, 400.0f, -150.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    const uint32_t white = builder.addMaterial(colored("backdrop", glm::vec3(0.85f)));
    const float distances[9] = {3.0f, 6.0f, 12.0f, 20.0f, 32.0f, 50.0f, 75.0f, 105.0f, 145.0f};
    for (int i = 0; i < 9; ++i) {
        const float d = distances[i], size = std::max(0.5f, 0.05f * d);
        const float x = d * std::tan(glm::radians(i % 2 == 0 ? 14.0f : -16.0f));
        const std::string tag = std::to_string(int(d)) + "m";
        addBox(builder, glm::vec3(0.5f * size), red, at({x, 0.5f * size, -d}), "box_" + tag);
        addSphere(builder, 0.5f * size, blue, {x + 1.6f * size, 0.5f * size, -d}, "sphere_" + tag);
        if (d >= 50.0f)
            addBox(builder, {3.5f * size, 1.2f * size, 0.1f * size}, white, at({x + 0.8f * size, 1.2f * size, -d - size}),
                   "wall_" + tag);
    }
    builder.addLight(sunFrom(40.0f, 30.0f));
    setCamera(builder, {0.0f, 1.7f, 0.0f}, {0.0f, 0.6f, -20.0f}, 60.0f);
    return builder.build();
}

// 2 and 5 cm walls, poles of 2-5 cm diameter and a 1 cm slab 2 cm above the floor: shadows that begin
// within a texel or two of their caster, where over-bias shows first.
Scene makeThinSlabs() {
    SceneBuilder builder;
    addGround(builder, 40.0f);
    const uint32_t white = builder.addMaterial(colored("slab", glm::vec3(0.85f)));
    addBox(builder, {0.75f, 0.5f, 0.01f}, white, at({-1.5f, 0.5f, -3.0f}), "wall_2cm");
    addBox(builder, {0.75f, 0.5f, 0.025f}, white, rotated(at({1.5f, 0.5f, -3.5f}), -25.0f, {0, 1, 0}), "wall_5cm");
    const float radii[3] = {0.01f, 0.015f, 0.025f};
    for (int i = 0; i < 3; ++i)
        addPole(builder, radii[i], 1.5f, white, {-0.6f + 0.6f * float(i), 0.0f, -1.8f},
                "pole_" + std::to_string(int(200.0f * radii[i])) + "cm");
    addBox(builder, {0.5f, 0.005f, 0.5f}, white, at({0.3f, 0.025f, -0.6f}), "slab_1cm_at_2cm");
    builder.addLight(sunFrom(40.0f, 150.0f));
    setCamera(builder, {0.0f, 2.2f, 2.2f}, {0.0f, 0.2f, -2.2f}, 55.0f);
    return builder.build();
}

// The sun 10° above the horizon over a floor, slabs on it tilted 4-16° toward the sun, and curved
// terminators (spheres, a lying cylinder) where N·L goes to 0 across a smooth surface.
Scene makeGrazingSun() {
    SceneBuilder builder;
    addGround(builder, 120.0f, -20.0f);
    const uint32_t white = builder.addMaterial(colored("slab", glm::vec3(0.85f)));
    const uint32_t blue = builder.addMaterial(colored("curved", {0.2f, 0.35f, 0.8f}));
    const float tilts[4] = {4.0f, 8.0f, 12.0f, 16.0f};
    for (int i = 0; i < 4; ++i) {
        // Hinged on the floor at its edge toward the sun (+X), rising away from it: tilted toward the sun.
        const glm::mat4 pose = rotated(at({-3.0f + 3.0f * float(i), 0.0f, -6.0f - 2.0f * float(i)}), -tilts[i], {0, 0, 1});
        addBox(builder, {1.2f, 0.05f, 0.8f}, white, pose * at({-1.2f, 0.05f, 0.0f}),
               "slab_" + std::to_string(int(tilts[i])) + "deg");
    }
    addSphere(builder, 0.5f, blue, {-2.0f, 0.5f, -3.0f}, "sphere_50cm");
    addSphere(builder, 1.0f, blue, {3.0f, 1.0f, -12.0f}, "sphere_1m");
    builder.addInstance(builder.addMesh(makeCylinderMesh(0.4f, 3.0f, blue, 32)),
                        rotated(at({0.5f, 0.4f, -16.0f}), 90.0f, {1, 0, 0}),
                        true, "lying_cylinder");
    builder.addLight(sunFrom(10.0f, 80.0f));
    setCamera(builder, {0.0f, 3.0f, 4.0f}, {0.0f, 0.0f, -9.0f}, 60.0f);
    return builder.build();
}

namespace {

TextureSampler nearestSampler() {
    TextureSampler sampler;
    sampler.magFilter = sampler.minFilter = TextureFilter::Nearest;
    sampler.mipmaps = MipmapMode::None;
    return sampler;
}

// A picket fence: 64 x 16 texels, pickets 3 texels wide with 1-texel gaps, two rails, top 3 rows clear.
Texture makeFenceTexture() {
    Texture texture;
    texture.name = "fence";
    texture.rgba = Image(64, 16, 4);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const bool picket = x % 4 != 3 && y >= 3;
            const bool rail = (y >= 6 && y <= 7) || (y >= 12 && y <= 13);
            texture.rgba.at(x, y, 0) = 170, texture.rgba.at(x, y, 1) = 130, texture.rgba.at(x, y, 2) = 90;
            texture.rgba.at(x, y, 3) = picket || rail ? 255 : 0;
        }
    texture.sampler = nearestSampler();
    return texture;
}

// A 16 x 16 leaf card: a diamond with a 2-texel hole, blocky under NEAREST magnification.
Texture makeCardTexture() {
    Texture texture;
    texture.name = "card";
    texture.rgba = Image(16, 16, 4);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const int dx = std::abs(2 * x - 15), dy = std::abs(2 * y - 15);
            const bool hole = dx <= 1 && dy <= 5 && dy >= 2;
            texture.rgba.at(x, y, 0) = 60, texture.rgba.at(x, y, 1) = 150, texture.rgba.at(x, y, 2) = 40;
            texture.rgba.at(x, y, 3) = dx + dy < 16 && !hole ? 255 : 0;
        }
    texture.sampler = nearestSampler();
    return texture;
}

Material maskMaterial(const char* name, int texture) {
    Material material = colored(name, glm::vec3(1.0f));
    material.baseColorTexture = texture;
    material.alphaMode = AlphaMode::Mask;
    material.alphaCutoff = 0.5f;
    material.doubleSided = true;
    material.shadows = MaterialShadowMode::Clip;
    return material;
}

}  // namespace

// Alpha-MASK foliage cards and a picket fence whose textures are NEAREST-sampled (glTF sampler 9728):
// shadows with square texel edges, as the material's texels give them.
Scene makeFence() {
    SceneBuilder builder;
    addGround(builder, 40.0f);
    const uint32_t fence = builder.addMaterial(maskMaterial("fence_mask", int(builder.addTexture(makeFenceTexture()))));
    const uint32_t card = builder.addMaterial(maskMaterial("card_mask", int(builder.addTexture(makeCardTexture()))));
    const uint32_t fenceQuad = builder.addMesh(makeQuadMesh({8.0f, 1.5f}, fence));
    builder.addInstance(fenceQuad, rotated(at({0.0f, 0.75f, -4.0f}), 8.0f, {0, 1, 0}), true, "fence");
    const uint32_t cardQuad = builder.addMesh(makeQuadMesh({1.2f, 1.2f}, card));
    const glm::vec3 positions[4] = {{-2.5f, 1.4f, -1.5f}, {-0.5f, 1.8f, -2.0f}, {1.6f, 1.2f, -1.2f}, {3.0f, 2.2f, -2.6f}};
    const float turns[4] = {30.0f, -20.0f, 65.0f, 5.0f};
    const float tilts[4] = {-60.0f, 10.0f, -25.0f, -80.0f};
    for (int i = 0; i < 4; ++i)
        builder.addInstance(cardQuad, rotated(rotated(at(positions[i]), turns[i], {0, 1, 0}), tilts[i], {1, 0, 0}), true,
                            "card_" + std::to_string(i));
    builder.addLight(sunFrom(50.0f, 35.0f));
    setCamera(builder, {0.0f, 3.0f, 4.5f}, {0.0f, 0.4f, -3.0f}, 55.0f);
    return builder.build();
}

// 576 small boxes, spheres and poles on a 24 x 24 grid over 70 m x 100 m: many small shadows in every
// cascade (three shared meshes, scaled per instance).
Scene makeFieldOfObjects() {
    SceneBuilder builder;
    addGround(builder, 240.0f, -50.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    const uint32_t meshes[3] = {builder.addMesh(makeBoxMesh(glm::vec3(0.5f), red)),
                                builder.addMesh(makeSphereMesh(0.5f, blue, 16, 8)),
                                builder.addMesh(makeCylinderMesh(0.5f, 1.0f, red, 12))};
    for (int row = 0; row < 24; ++row)
        for (int column = 0; column < 24; ++column) {
            const int kind = (row * 7 + column * 3) % 3;
            const float size = 0.3f + 0.1f * float((row * 5 + column * 11) % 4);
            const glm::vec3 base(-35.0f + 70.0f * float(column) / 23.0f + 0.6f * float(row % 2),
                                 0.0f, -2.0f - 100.0f * float(row) / 23.0f);
            const glm::vec3 scale = kind == 2 ? glm::vec3(0.3f * size, 2.5f * size, 0.3f * size) : glm::vec3(size);
            const glm::vec3 offset = kind == 2 ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.5f * size, 0.0f);
            builder.addInstance(meshes[kind], glm::scale(at(base + offset), scale), true,
                                "object_" + std::to_string(row) + "_" + std::to_string(column));
        }
    builder.addLight(sunFrom(45.0f, 25.0f));
    setCamera(builder, {0.0f, 6.0f, 6.0f}, {0.0f, 0.0f, -30.0f}, 60.0f);
    return builder.build();
}

// The simplest case: a 2 m cube on a plane under a 45° sun.
Scene makeCube() {
    SceneBuilder builder;
    addGround(builder, 40.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    addBox(builder, glm::vec3(1.0f), red, at({0.0f, 1.0f, 0.0f}), "cube_2m");
    builder.addLight(sunFrom(45.0f, -70.0f));
    setCamera(builder, {4.0f, 4.5f, 7.0f}, {-0.5f, 0.5f, -0.5f}, 50.0f);
    return builder.build();
}

// The engine of the glTF sample models (2CylinderEngine, 121k triangles in millimetres, parts that
// leave cracks between them), in metres on a ground: light 0 a 35° sun, light 1 a spot above it.
Scene makeCadEngine() {
    if (!std::filesystem::exists(kCadEngineSamplePath))
        throw Error(std::string("the CAD scene needs ") + kCadEngineSamplePath + " (Debian package assimp-testmodels)");
    const Scene engine = loadGltfScene(kCadEngineSamplePath);
    SceneBuilder builder;
    addGround(builder, 20.0f);
    const uint32_t firstMaterial = 1;  // after the ground's
    for (const Material& m : engine.materials) builder.addMaterial(m);
    const glm::vec3 size = engine.wsBounds.extent() * 0.001f;
    const glm::vec3 centre = engine.wsBounds.center() * 0.001f;
    // Millimetres to metres, centred over the origin, resting on the ground.
    const glm::mat4 placement = glm::scale(at({-centre.x, 0.5f * size.y - centre.y, -centre.z}), glm::vec3(0.001f));
    std::vector<int> meshOf(engine.meshes.size(), -1);  // the engine reuses meshes across nodes
    for (const Instance& instance : engine.instances) {
        if (meshOf[instance.meshIndex] < 0) {
            Mesh mesh = engine.meshes[instance.meshIndex];
            mesh.materialIndex += firstMaterial;
            meshOf[instance.meshIndex] = int(builder.addMesh(std::move(mesh)));
        }
        builder.addInstance(uint32_t(meshOf[instance.meshIndex]), placement * instance.worldFromObject, true,
                            instance.nodeName);
    }
    builder.addLight(sunFrom(35.0f, 40.0f));
    const float extent = std::max({size.x, size.y, size.z});
    Light spot = makeSpotLight({0.6f * extent, 1.8f * extent, 0.9f * extent}, -glm::vec3(0.6f, 1.5f, 0.9f), 6.0f,
                               6.0f * extent, glm::radians(40.0f), glm::radians(30.0f));
    spot.name = "spot";
    spot.shadows = LightShadows::Soft;
    builder.addLight(spot);
    setCamera(builder, {0.55f * extent, 0.7f * extent, 1.0f * extent}, {0.0f, 0.3f * size.y, 0.0f}, 50.0f);
    return builder.build();
}

// Three shadowed spot lights (two soft, one hard) over a box, a ball, a pole and a shelf on a wall.
Scene makeSpotShelf() {
    SceneBuilder builder;
    addGround(builder, 20.0f);
    const uint32_t white = builder.addMaterial(colored("wall", glm::vec3(0.85f)));
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    addBox(builder, {4.0f, 1.75f, 0.1f}, white, at({0.0f, 1.75f, -4.0f}), "back_wall");
    addBox(builder, {0.9f, 0.02f, 0.25f}, white, at({0.8f, 1.2f, -3.65f}), "shelf");
    for (float x : {0.05f, 1.55f}) addBox(builder, {0.02f, 0.15f, 0.2f}, white, at({x, 1.03f, -3.7f}), "shelf_bracket");
    addBox(builder, glm::vec3(0.15f), red, at({0.5f, 1.37f, -3.7f}), "box_on_shelf");
    addBox(builder, glm::vec3(0.35f), red, at({-1.6f, 0.35f, -2.6f}), "box");
    addSphere(builder, 0.3f, blue, {-0.3f, 0.3f, -1.8f}, "ball");
    addPole(builder, 0.04f, 1.8f, blue, {1.6f, 0.0f, -2.0f}, "pole");
    const glm::vec3 positions[3] = {{-2.2f, 3.2f, -0.5f}, {0.8f, 3.0f, -1.0f}, {2.6f, 2.6f, 0.0f}};
    const glm::vec3 targets[3] = {{-1.2f, 0.0f, -2.6f}, {0.6f, 1.0f, -3.6f}, {1.2f, 0.0f, -2.5f}};
    const char* names[3] = {"spot_box", "spot_shelf", "spot_pole"};
    for (int i = 0; i < 3; ++i) {
        Light spot = makeSpotLight(positions[i], targets[i] - positions[i], 40.0f, 12.0f, glm::radians(38.0f),
                                   glm::radians(28.0f));
        spot.name = names[i];
        spot.shadows = i == 2 ? LightShadows::Hard : LightShadows::Soft;
        builder.addLight(spot);
    }
    setCamera(builder, {0.0f, 2.6f, 3.2f}, {0.0f, 0.8f, -2.6f}, 60.0f);
    return builder.build();
}

}  // namespace penumbra::canonical

namespace penumbra::canonical {

// Contact-hardening soft shadows (shadows "pcss"): a pole, a box and a plate raised 1 m, so penumbrae
// grow from sharp at contacts to wide away from them; light 0 a sun 3° wide, light 1 a spot with a
// 15 cm emitter, both shadows "pcss". Compare with penumbra compare --soft N.
Scene makePcssContact() {
    SceneBuilder builder;
    addGround(builder, 40.0f);
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    addPole(builder, 0.05f, 2.5f, blue, {-1.5f, 0.0f, -3.0f}, "pole");
    addBox(builder, glm::vec3(0.4f), red, at({0.3f, 0.4f, -4.0f}), "box");
    addBox(builder, {0.6f, 0.03f, 0.6f}, red, at({2.0f, 1.0f, -3.5f}), "plate_1m");
    Light sun = sunFrom(50.0f, 120.0f);
    sun.shadows = LightShadows::Pcss;
    sun.shadowLightSize = 3.0f;
    builder.addLight(sun);
    Light spot = makeSpotLight({0.5f, 4.0f, -1.0f}, glm::vec3(0.5f, 0.0f, -3.8f) - glm::vec3(0.5f, 4.0f, -1.0f), 60.0f,
                               12.0f, glm::radians(45.0f), glm::radians(35.0f));
    spot.name = "spot_pcss";
    spot.shadows = LightShadows::Pcss;
    spot.shadowLightSize = 0.15f;
    builder.addLight(spot);
    setCamera(builder, {0.0f, 3.0f, 2.0f}, {0.3f, 0.3f, -3.5f}, 55.0f);
    return builder.build();
}

}  // namespace penumbra::canonical

namespace penumbra::canonical {

// A point light 2.5 m above the floor, 1 m from each wall of a room corner: shadows of a box, a pole,
// a table and a ball fall on the floor and on both walls, through five of the light's six cube faces
// (down, the two walls', and the floor beyond 2.5 m on the open sides), so every face's bias and its
// edges show. Shadows that start late at a contact (too much bias) show as false lit.
Scene makeRoomCorner() {
    SceneBuilder builder;
    addGround(builder, 16.0f);
    const uint32_t white = builder.addMaterial(colored("walls", glm::vec3(0.85f)));
    const uint32_t red = builder.addMaterial(colored("caster", {0.8f, 0.3f, 0.2f}));
    const uint32_t blue = builder.addMaterial(colored("caster_blue", {0.2f, 0.35f, 0.8f}));
    addBox(builder, {0.1f, 1.6f, 5.0f}, white, at({-4.1f, 1.6f, -5.0f}), "wall_left");
    addBox(builder, {5.0f, 1.6f, 0.1f}, white, at({0.0f, 1.6f, -9.1f}), "wall_back");
    addBox(builder, glm::vec3(0.35f), red, at({-2.6f, 0.35f, -6.6f}), "box_corner");
    addPole(builder, 0.05f, 2.0f, blue, {-1.6f, 0.0f, -8.3f}, "pole_wall");
    addBox(builder, {0.5f, 0.03f, 0.4f}, red, at({-0.4f, 0.8f, -6.2f}), "table_top");
    for (float dx : {-0.45f, 0.45f})
        for (float dz : {-0.35f, 0.35f}) addPole(builder, 0.03f, 0.77f, red, {-0.4f + dx, 0.0f, -6.2f + dz}, "table_leg");
    addSphere(builder, 0.3f, blue, {-2.8f, 0.3f, -3.8f}, "ball");
    addBox(builder, {0.25f, 0.5f, 0.25f}, blue, at({1.2f, 0.5f, -7.6f}), "block");
    Light bulb = makePointLight({-3.0f, 2.5f, -8.0f}, 30.0f, 15.0f);
    bulb.name = "bulb";
    builder.addLight(bulb);
    setCamera(builder, {2.5f, 3.2f, 0.5f}, {-1.8f, 0.7f, -6.5f}, 60.0f);
    return builder.build();
}

}  // namespace penumbra::canonical
