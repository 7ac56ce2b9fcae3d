#include "scene/demo_scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"

namespace penumbra {
namespace {

glm::mat4 at(glm::vec3 wsPosition) { return glm::translate(glm::mat4(1.0f), wsPosition); }

Material colored(const char* name, glm::vec3 rgb, float roughness = 0.8f) {
    Material material;
    material.name = name;
    material.baseColorFactor = glm::vec4(rgb, 1.0f);
    material.metallic = 0.0f;
    material.roughness = roughness;
    return material;
}

// A leaf-like pattern: green checker cells with round holes (alpha 0) to exercise clipped shadows.
Texture makeLeafTexture() {
    constexpr uint32_t kSize = 64, kCell = 16;
    Texture texture;
    texture.name = "leaf_checker";
    texture.rgba = Image(kSize, kSize, 4);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool dark = ((x / kCell) + (y / kCell)) % 2 == 1;
            const float dx = float(x % kCell) + 0.5f - kCell * 0.5f, dy = float(y % kCell) + 0.5f - kCell * 0.5f;
            const float holeRadius = 0.3f * kCell;
            const bool hole = dx * dx + dy * dy < holeRadius * holeRadius;
            texture.rgba.at(x, y, 0) = dark ? 40 : 90;
            texture.rgba.at(x, y, 1) = dark ? 120 : 190;
            texture.rgba.at(x, y, 2) = dark ? 30 : 60;
            texture.rgba.at(x, y, 3) = hole ? 0 : 255;
        }
    return texture;
}

void addNearObjects(SceneBuilder& builder) {
    const uint32_t red = builder.addMaterial(colored("red", {0.8f, 0.15f, 0.1f}));
    const uint32_t blue = builder.addMaterial(colored("blue", {0.15f, 0.3f, 0.85f}));
    const uint32_t green = builder.addMaterial(colored("green", {0.2f, 0.7f, 0.25f}, 0.4f));
    const uint32_t yellow = builder.addMaterial(colored("yellow", {0.9f, 0.8f, 0.2f}));
    const uint32_t white = builder.addMaterial(colored("wall", {0.85f, 0.85f, 0.8f}));
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), red)), at({-3.0f, 0.5f, 0.0f}), true, "red_box");
    builder.addInstance(builder.addMesh(makeBoxMesh({0.75f, 1.25f, 0.75f}, blue)), at({2.5f, 1.25f, -2.0f}), true,
                        "blue_box");
    builder.addInstance(builder.addMesh(makeSphereMesh(0.75f, green)), at({0.0f, 0.75f, 2.0f}), true, "green_sphere");
    builder.addInstance(builder.addMesh(makeSphereMesh(1.2f, yellow)), at({4.5f, 1.2f, 1.5f}), true, "yellow_sphere");
    builder.addInstance(builder.addMesh(makeCylinderMesh(0.35f, 3.0f, white)), at({-5.5f, 0.0f, -2.5f}), true, "pillar");
    builder.addInstance(builder.addMesh(makeBoxMesh({3.0f, 2.5f, 0.1f}, white)), at({-1.0f, 2.5f, -6.0f}), true, "wall");
}

void addFarObjects(SceneBuilder& builder) {
    const uint32_t orange = builder.addMaterial(colored("far_orange", {0.9f, 0.45f, 0.15f}));
    const uint32_t purple = builder.addMaterial(colored("far_purple", {0.55f, 0.3f, 0.75f}));
    builder.addInstance(builder.addMesh(makeBoxMesh({3.0f, 3.0f, 3.0f}, orange)), at({10.0f, 3.0f, -40.0f}), true,
                        "far_box");
    builder.addInstance(builder.addMesh(makeSphereMesh(4.0f, purple)), at({-15.0f, 4.0f, -70.0f}), true, "far_sphere");
    builder.addInstance(builder.addMesh(makeBoxMesh({1.5f, 8.0f, 1.5f}, orange)), at({22.0f, 8.0f, -55.0f}), true,
                        "far_tower");
}

void addSpecialMaterials(SceneBuilder& builder) {
    Material leaf = colored("leaf_mask", glm::vec3(1.0f));
    leaf.baseColorTexture = int(builder.addTexture(makeLeafTexture()));
    leaf.alphaMode = AlphaMode::Mask;
    leaf.alphaCutoff = 0.5f;
    leaf.doubleSided = true;
    leaf.shadows = MaterialShadowMode::Clip;
    const glm::mat4 quadPose = glm::rotate(at({-1.5f, 1.3f, -1.0f}), glm::radians(20.0f), glm::vec3(0, 1, 0));
    builder.addInstance(builder.addMesh(makeQuadMesh({2.5f, 2.5f}, builder.addMaterial(leaf))), quadPose, true,
                        "leaf_quad");

    Material glass = colored("glass_blend", {0.3f, 0.8f, 0.9f}, 0.1f);
    glass.baseColorFactor.a = 0.4f;
    glass.alphaMode = AlphaMode::Blend;
    glass.shadows = MaterialShadowMode::Dither;
    builder.addInstance(builder.addMesh(makeSphereMesh(0.8f, builder.addMaterial(glass))), at({2.0f, 0.8f, 4.0f}),
                        true, "glass_sphere");

    Material glow = colored("unlit_magenta", {1.0f, 0.2f, 0.8f});
    glow.unlit = true;
    glow.receiveShadows = false;
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.3f), builder.addMaterial(glow))),
                        at({-4.0f, 0.3f, 3.0f}), true, "unlit_box");
}

void addLights(SceneBuilder& builder) {
    // Sun from ~50 degrees elevation, behind-right of the camera's view, warm white, ~3 lux.
    const float elevation = glm::radians(50.0f), azimuth = glm::radians(35.0f);
    const glm::vec3 wsToSun(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                            -std::cos(elevation) * std::cos(azimuth));
    Light sun = makeDirectionalLight(-wsToSun, 3.0f, {1.0f, 0.95f, 0.85f});
    sun.name = "sun";
    sun.shadows = LightShadows::Soft;
    builder.addLight(sun);
    // Spots: illuminance = I / d^2; ~7 m and ~8 m from their targets, ~1.5-2 lux there.
    Light warm = makeSpotLight({-5.0f, 5.0f, 3.0f}, glm::vec3(-2.0f, 0.0f, 0.0f) - glm::vec3(-5.0f, 5.0f, 3.0f), 90.0f,
                               18.0f, glm::radians(35.0f), glm::radians(25.0f));
    warm.name = "spot_warm";
    warm.color = {1.0f, 0.6f, 0.3f};
    warm.shadows = LightShadows::Soft;
    builder.addLight(warm);
    Light cool = makeSpotLight({6.0f, 6.0f, 4.0f}, glm::vec3(3.0f, 0.0f, -0.5f) - glm::vec3(6.0f, 6.0f, 4.0f), 120.0f,
                               20.0f, glm::radians(30.0f), glm::radians(20.0f));
    cool.name = "spot_cool";
    cool.color = {0.4f, 0.6f, 1.0f};
    cool.shadows = LightShadows::Hard;
    builder.addLight(cool);
}

}  // namespace

Scene makeDemoScene() {
    SceneBuilder builder;
    const uint32_t ground = builder.addMaterial(colored("ground", glm::vec3(0.6f)));
    builder.addInstance(builder.addMesh(makePlaneMesh({60.0f, 60.0f}, ground, 30.0f)), glm::mat4(1.0f), true, "ground");
    addNearObjects(builder);
    addFarObjects(builder);
    addSpecialMaterials(builder);
    addLights(builder);
    Camera camera = makeLookAtCamera({0.0f, 6.0f, 16.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(55.0f));
    camera.name = "camera";
    builder.setCamera(camera);
    return builder.build();
}

}  // namespace penumbra
