// The built-in demo scene holds what it needs to exercise every shadow path.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "scene/demo_scene.h"

using namespace penumbra;

namespace {

const Material* findMaterial(const Scene& scene, AlphaMode mode) {
    for (const Material& m : scene.materials)
        if (m.alphaMode == mode) return &m;
    return nullptr;
}

}  // namespace

TEST(DemoScene, HasASunAndTwoShadowedColouredSpotLights) {
    const Scene scene = makeDemoScene();
    ASSERT_GE(scene.lights.size(), 3u);
    const Light& sun = scene.lights[0];
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_NE(sun.shadows, LightShadows::None);
    const float elevation = std::asin(-sun.wsDirection.y);
    EXPECT_NEAR(elevation, 50.0f * 3.14159265f / 180.0f, 0.05f);
    EXPECT_GT(sun.intensity, 2.0f);
    EXPECT_LT(sun.intensity, 4.0f);
    int spots = 0;
    for (const Light& light : scene.lights) {
        if (light.type != LightType::Spot) continue;
        ++spots;
        EXPECT_NE(light.shadows, LightShadows::None);
        EXPECT_NE(light.color, glm::vec3(1.0f));
        EXPECT_GE(light.range, 15.0f);
        EXPECT_LE(light.range, 20.0f);
        EXPECT_NEAR(glm::length(light.wsDirection), 1.0f, 1e-5f);
        EXPECT_LT(light.innerConeAngle, light.outerConeAngle);
    }
    EXPECT_EQ(spots, 2);
}

TEST(DemoScene, SpotLightsAimAtLitGroundWithModerateIlluminance) {
    const Scene scene = makeDemoScene();
    for (const Light& light : scene.lights) {
        if (light.type != LightType::Spot) continue;
        // Where the spot's axis meets the ground: illuminance I cos(theta) / d^2 should be ~0.5..pi lux.
        ASSERT_LT(light.wsDirection.y, 0.0f);
        const float distance = -light.wsPosition.y / light.wsDirection.y;
        EXPECT_LT(distance, light.range);
        const float lux = light.intensity * -light.wsDirection.y / (distance * distance);
        EXPECT_GT(lux, 0.5f);
        EXPECT_LT(lux, 3.2f);
    }
}

TEST(DemoScene, HasACameraAboveTheGroundLookingAtTheCentre) {
    const Scene scene = makeDemoScene();
    ASSERT_TRUE(scene.camera.has_value());
    const glm::vec3 wsEye(scene.camera->worldFromView[3]);
    const glm::vec3 wsForward = -glm::vec3(scene.camera->worldFromView[2]);
    EXPECT_GT(wsEye.y, 1.0f);
    EXPECT_LT(wsForward.y, 0.0f);
    EXPECT_GT(scene.camera->yfov, 0.8f);
    EXPECT_LT(scene.camera->yfov, 1.1f);
}

TEST(DemoScene, GroundIsLargeAndFarObjectsMakeCascadesMatter) {
    const Scene scene = makeDemoScene();
    EXPECT_GE(scene.wsBounds.extent().x, 60.0f);
    EXPECT_GE(scene.wsBounds.extent().z, 60.0f);
    const glm::vec3 wsEye(scene.camera->worldFromView[3]);
    float farthest = 0.0f;
    for (const Instance& instance : scene.instances)
        if (instance.nodeName != "ground") farthest = std::max(farthest, glm::length(instance.wsBounds.center() - wsEye));
    EXPECT_GT(farthest, 40.0f + 16.0f);
}

TEST(DemoScene, HasClippedDitheredAndUnlitMaterials) {
    const Scene scene = makeDemoScene();
    const Material* mask = findMaterial(scene, AlphaMode::Mask);
    ASSERT_NE(mask, nullptr);
    EXPECT_EQ(mask->shadows, MaterialShadowMode::Clip);
    ASSERT_GE(mask->baseColorTexture, 0);
    const Image& rgba = scene.textures[size_t(mask->baseColorTexture)].rgba;
    size_t holes = 0;
    for (size_t i = 3; i < rgba.pixels.size(); i += 4) holes += rgba.pixels[i] == 0;
    EXPECT_GT(holes, 0u);
    EXPECT_LT(holes, rgba.pixels.size() / 4);
    const Material* blend = findMaterial(scene, AlphaMode::Blend);
    ASSERT_NE(blend, nullptr);
    EXPECT_EQ(blend->shadows, MaterialShadowMode::Dither);
    EXPECT_LT(blend->baseColorFactor.a, 1.0f);
    EXPECT_TRUE(std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.unlit; }));
}

TEST(DemoScene, EveryInstanceUsesAValidMeshAndMaterial) {
    const Scene scene = makeDemoScene();
    for (const Instance& instance : scene.instances) {
        ASSERT_LT(instance.meshIndex, scene.meshes.size());
        const Mesh& mesh = scene.meshes[instance.meshIndex];
        EXPECT_LT(mesh.materialIndex, scene.materials.size());
        EXPECT_FALSE(mesh.indices.empty());
        EXPECT_TRUE(instance.wsBounds.valid());
    }
    EXPECT_GE(scene.instances.size(), 10u);
}
