// ShadowPlanner::plan into a ShadowFrame and workspace that planned another frame before (how the
// renderer plans every frame without a heap allocation) gives exactly the plan of a fresh call.
#include <cstring>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/shadow_planner.h"
#include "spot_test_scenes.h"

using namespace penumbra;

namespace {

// 20 shadowed spot lights (4 of them dropped: 16 tiles), a ground, boxes, and one directional light.
Scene crowdedScene() {
    Scene scene = test::spotGridScene(20);
    shadow_test::addDirectionalLight(scene, {0.3f, -1.0f, 0.2f});
    return scene;
}

// 3 spot lights and two directional lights, seen from elsewhere.
Scene smallScene() {
    Scene scene = test::spotGridScene(3, LightShadows::Hard);
    shadow_test::addDirectionalLight(scene, {-0.2f, -1.0f, 0.4f});
    shadow_test::addDirectionalLight(scene, {0.5f, -0.8f, -0.1f});
    return scene;
}

ShadowSettings settingsOf(uint32_t cascades) {
    ShadowSettings settings = shadow_test::sphereCascadeSettings();
    settings.directional.cascadeCount = cascades;
    return settings;
}

template <typename T>
bool sameBytes(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

void expectSameTiles(const std::vector<ShadowTile>& reused, const std::vector<ShadowTile>& fresh) {
    ASSERT_EQ(reused.size(), fresh.size());
    for (size_t i = 0; i < fresh.size(); ++i) {
        EXPECT_EQ(reused[i].lightSlot, fresh[i].lightSlot);
        EXPECT_EQ(reused[i].cascadeIndex, fresh[i].cascadeIndex);
        EXPECT_EQ(reused[i].rect.offset, fresh[i].rect.offset);
        EXPECT_EQ(reused[i].rect.size, fresh[i].rect.size);
        EXPECT_EQ(reused[i].atlasFromWorld, fresh[i].atlasFromWorld);
        EXPECT_EQ(reused[i].casterInstances, fresh[i].casterInstances);
    }
}

void expectSamePlan(const ShadowFrame& reused, const ShadowFrame& fresh) {
    EXPECT_EQ(reused.directional.lights.size(), fresh.directional.lights.size());
    EXPECT_EQ(reused.directional.cascades.size(), fresh.directional.cascades.size());
    EXPECT_EQ(reused.directional.slotOfSceneLight, fresh.directional.slotOfSceneLight);
    EXPECT_TRUE(sameBytes(reused.directional.gpu, fresh.directional.gpu));
    expectSameTiles(reused.directional.tiles, fresh.directional.tiles);
    EXPECT_EQ(reused.other.lights.size(), fresh.other.lights.size());
    EXPECT_EQ(reused.other.slotOfSceneLight, fresh.other.slotOfSceneLight);
    EXPECT_EQ(reused.other.droppedLights, fresh.other.droppedLights);
    EXPECT_EQ(reused.other.warnings, fresh.other.warnings);
    EXPECT_EQ(reused.other.specializationMode, fresh.other.specializationMode);
    EXPECT_TRUE(sameBytes(reused.other.gpu, fresh.other.gpu));
    expectSameTiles(reused.other.tiles, fresh.other.tiles);
    EXPECT_EQ(reused.stats.castersPerTile, fresh.stats.castersPerTile);
    EXPECT_EQ(reused.stats.shadowCasters, fresh.stats.shadowCasters);
    EXPECT_EQ(reused.stats.casterDraws, fresh.stats.casterDraws);
    EXPECT_EQ(reused.stats.directionalLightsConsidered, fresh.stats.directionalLightsConsidered);
}

// Plans `first` then `second` into one frame and workspace, and compares with a fresh plan of `second`.
void expectReusedPlanIsFresh(const Scene& first, const ShadowSettings& firstSettings, const Scene& second,
                             const ShadowSettings& secondSettings, bool cullCasters) {
    const CameraView firstCamera = resolveCameraView(first, 96, 54);
    const CameraView secondCamera = shadow_test::cameraLookingAt({3, 8, 12}, {0, 0, 0});
    PlanOptions options;
    options.cullCasters = cullCasters;
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    ShadowPlanner::plan(first, firstCamera, firstSettings, nullptr, options, frame, workspace);
    ShadowPlanner::plan(second, secondCamera, secondSettings, nullptr, options, frame, workspace);
    expectSamePlan(frame, ShadowPlanner::plan(second, secondCamera, secondSettings, nullptr, options));
}

}  // namespace

TEST(ShadowPlanReuse, AFewerLightsPlanIntoACrowdedFramesStorageEqualsItsFreshPlan) {
    expectReusedPlanIsFresh(crowdedScene(), settingsOf(4), smallScene(), settingsOf(2), false);
}

TEST(ShadowPlanReuse, ACrowdedPlanIntoASmallFramesStorageEqualsItsFreshPlan) {
    expectReusedPlanIsFresh(smallScene(), settingsOf(2), crowdedScene(), settingsOf(4), false);
}

TEST(ShadowPlanReuse, PlansWithCpuCasterListsReuseStorageToo) {
    expectReusedPlanIsFresh(crowdedScene(), settingsOf(3), smallScene(), settingsOf(4), true);
}

TEST(ShadowPlanReuse, DroppedLightWarningsOfAnEarlierFrameDoNotStay) {
    const Scene crowded = crowdedScene(), small = smallScene();
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    const CameraView camera = resolveCameraView(crowded, 96, 54);
    ShadowPlanner::plan(crowded, camera, settingsOf(4), nullptr, {}, frame, workspace);
    ASSERT_FALSE(frame.other.warnings.empty());
    ShadowPlanner::plan(small, camera, settingsOf(4), nullptr, {}, frame, workspace);
    EXPECT_TRUE(frame.other.warnings.empty());
    EXPECT_TRUE(frame.other.droppedLights.empty());
}

// The first instance of `scene` that casts shadows stops casting.
void stopFirstCaster(Scene& scene) {
    for (Instance& instance : scene.instances)
        if (instance.castShadows) {
            instance.castShadows = false;
            return;
        }
}

TEST(ShadowPlanReuse, AWorkspaceKeepsTheCasterListOfTheSameSceneVersion) {
    Scene scene = smallScene();
    const CameraView camera = resolveCameraView(scene, 96, 54);
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    PlanOptions options;
    options.sceneVersion = 7;
    ShadowPlanner::plan(scene, camera, settingsOf(2), nullptr, options, frame, workspace);
    const uint32_t casters = frame.stats.shadowCasters;
    stopFirstCaster(scene);  // without a new version: the caller promised the scene did not change
    ShadowPlanner::plan(scene, camera, settingsOf(2), nullptr, options, frame, workspace);
    EXPECT_EQ(frame.stats.shadowCasters, casters) << "the kept list: no walk over the instances";
    options.sceneVersion = 8;
    ShadowPlanner::plan(scene, camera, settingsOf(2), nullptr, options, frame, workspace);
    EXPECT_EQ(frame.stats.shadowCasters, casters - 1) << "a new version walks them again";
}

TEST(ShadowPlanReuse, WithoutASceneVersionEveryPlanWalksTheInstances) {
    Scene scene = smallScene();
    const CameraView camera = resolveCameraView(scene, 96, 54);
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    ShadowPlanner::plan(scene, camera, settingsOf(2), nullptr, {}, frame, workspace);
    const uint32_t casters = frame.stats.shadowCasters;
    stopFirstCaster(scene);
    ShadowPlanner::plan(scene, camera, settingsOf(2), nullptr, {}, frame, workspace);
    EXPECT_EQ(frame.stats.shadowCasters, casters - 1);
}
