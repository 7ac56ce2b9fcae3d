// The public planner (penumbra/shadow_plan.h): planShadows is ShadowPlanner's frame as plain data.
#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "penumbra/scene_builder.h"
#include "penumbra/shadow_plan.h"
#include "shadows/shadow_planner.h"

namespace penumbra {
namespace {

// A ground, a box on it and a box 500 m away; a sun, a spot light and a point light, all shadowed.
Scene sunSpotPointScene() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    builder.addInstance(builder.addMesh(makePlaneMesh({30.0f, 30.0f}, material)), glm::mat4(1.0f));
    const uint32_t box = builder.addMesh(makeBoxMesh({0.5f, 0.5f, 0.5f}, material));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {500.0f, 0.5f, 500.0f}));
    builder.addLight(makeDirectionalLight({0.3f, -1.0f, -0.4f}, 3.0f));
    builder.addLight(makeSpotLight({2.0f, 4.0f, 2.0f}, {-0.4f, -1.0f, -0.4f}, 50.0f, 20.0f, 0.8f, 0.6f));
    builder.addLight(makePointLight({-2.0f, 2.0f, 1.0f}, 30.0f, 15.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 4.0f, 9.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
    return builder.build();
}

TEST(ShadowPlan, EveryReservedLightGetsItsMapsInsideItsAtlas) {
    const Scene scene = sunSpotPointScene();
    const CameraView view = resolveCameraView(scene, 640, 360);
    const ShadowSettings settings;
    const ShadowPlan plan = planShadows(scene, view, settings);
    ASSERT_EQ(plan.directionalMaps.size(), settings.directional.cascadeCount);
    ASSERT_EQ(plan.cascades.size(), settings.directional.cascadeCount);
    for (uint32_t i = 0; i < plan.directionalMaps.size(); ++i) {
        const PlannedShadowMap& map = plan.directionalMaps[i];
        EXPECT_EQ(map.sceneLight, 0u);
        EXPECT_EQ(map.cascade, i);
        EXPECT_FALSE(map.perspective);
        EXPECT_LE(map.atlasX + map.size, plan.directionalAtlasSize);
        EXPECT_LE(map.atlasY + map.size, plan.directionalAtlasSize);
    }
    ASSERT_EQ(plan.otherMaps.size(), 7u);  // the spot light's map and the point light's six faces
    EXPECT_EQ(std::count_if(plan.otherMaps.begin(), plan.otherMaps.end(), [](const PlannedShadowMap& m) { return m.sceneLight == 1; }), 1);
    EXPECT_EQ(std::count_if(plan.otherMaps.begin(), plan.otherMaps.end(), [](const PlannedShadowMap& m) { return m.sceneLight == 2; }), 6);
    for (const PlannedShadowMap& map : plan.otherMaps) {
        EXPECT_TRUE(map.perspective);
        EXPECT_LE(map.atlasX + map.size, plan.otherAtlasSize);
    }
    EXPECT_TRUE(plan.droppedLights.empty());
}

TEST(ShadowPlan, MapsAreThePlannersTilesWithTheSphereFit) {
    const Scene scene = sunSpotPointScene();
    const CameraView view = resolveCameraView(scene, 640, 360);
    ShadowSettings settings;
    const ShadowPlan plan = planShadows(scene, view, settings);
    settings.directional.fit = CascadeFit::Sphere;
    const ShadowFrame frame = ShadowPlanner::plan(scene, view, settings);
    ASSERT_EQ(plan.directionalMaps.size(), frame.directional.tiles.size());
    for (size_t i = 0; i < frame.directional.tiles.size(); ++i) {
        EXPECT_EQ(plan.directionalMaps[i].clipFromWorld, frame.directional.tiles[i].clipFromWorld);
        EXPECT_EQ(plan.directionalMaps[i].atlasFromWorld, frame.directional.tiles[i].atlasFromWorld);
        EXPECT_EQ(plan.directionalMaps[i].casterInstances, frame.directional.tiles[i].casterInstances);
        EXPECT_FLOAT_EQ(plan.cascades[i].radius, frame.directional.cascades[i].radius);
    }
    ASSERT_EQ(plan.otherMaps.size(), frame.other.tiles.size());
    for (size_t i = 0; i < frame.other.tiles.size(); ++i)
        EXPECT_EQ(plan.otherMaps[i].clipFromWorld, frame.other.tiles[i].clipFromWorld);
}

TEST(ShadowPlan, AMapListsTheCastersItsVolumeHoldsAndNotOnesFarAway) {
    const Scene scene = sunSpotPointScene();
    const ShadowPlan plan = planShadows(scene, resolveCameraView(scene, 640, 360), ShadowSettings{});
    // The box in view, 10 m from the camera, is in the cascades that cover it, not in all of them.
    size_t mapsWithTheBox = 0;
    for (const PlannedShadowMap& map : plan.directionalMaps)
        mapsWithTheBox += std::find(map.casterInstances.begin(), map.casterInstances.end(), 1u) != map.casterInstances.end();
    EXPECT_GE(mapsWithTheBox, 1u) << "the box in view";
    EXPECT_LT(mapsWithTheBox, plan.directionalMaps.size()) << "not every cascade";
    for (const PlannedShadowMap& map : plan.directionalMaps)
        EXPECT_EQ(std::find(map.casterInstances.begin(), map.casterInstances.end(), 2u), map.casterInstances.end())
            << "the box 500 m away, beyond the shadow distance";
}

TEST(ShadowPlan, InvalidSettingsAreAnError) {
    const Scene scene = sunSpotPointScene();
    ShadowSettings settings;
    settings.directional.cascadeCount = 9;
    EXPECT_THROW(planShadows(scene, resolveCameraView(scene, 640, 360), settings), Error);
}

}  // namespace
}  // namespace penumbra
