// What the viewer's panels show, without a window (src/viewer/panel_data.h): the cascade split bar
// (the manual ratios, or a real plan's computed splits over the shadow distance), the stats panel's
// reserved and dropped lights from a real plan's stats JSON, and the camera combo's entries.
#include <gtest/gtest.h>

#include "render/shadow_stats_json.h"
#include "shadow_test_scene.h"
#include "shadows/shadow_planner.h"
#include "viewer/panel_data.h"

using namespace penumbra;
using namespace penumbra::shadow_test;
using namespace penumbra::viewer;

namespace {

Scene groundAndBox() {
    Scene scene = baseScene();
    addBox(scene, {-20, -1, -20}, {20, 0, 20});
    addBox(scene, {-1, 0, -1}, {1, 2, 1});
    return scene;
}

// The shadow stats of a frame of `scene` planned with `settings` (sphere fit: no depth reduction needed).
ShadowPlanStats statsOf(const Scene& scene, const Settings& settings) {
    return shadowPlanStats(ShadowPlanner::plan(scene, cameraLookingAt({0, 6, 15}, {0, 0, 0}), settings.shadows));
}

Settings settingsWithSplits(CascadeSplitMode mode) {
    Settings settings;
    settings.shadows.directional.fit = CascadeFit::Sphere;
    settings.shadows.directional.cascadeSplits = mode;
    settings.shadows.maxDistance = 40.0f;
    return settings;
}

}  // namespace

TEST(ViewerSplitBar, ManualSplitsAreTheRatiosAndTheLastCascadeEndsAtOne) {
    Settings settings = settingsWithSplits(CascadeSplitMode::Manual);
    settings.shadows.directional.cascadeCount = 3;
    settings.shadows.directional.cascadeRatios = {0.2f, 0.6f, 0.8f};
    const SplitBar bar = splitBarOf(settings, ShadowPlanStats{});
    EXPECT_FALSE(bar.computed);
    EXPECT_EQ(bar.ends, (std::vector<float>{0.2f, 0.6f, 1.0f}));
}

TEST(ViewerSplitBar, LogAndPracticalSplitsAreTheFramesSplitsOverTheShadowDistance) {
    Scene scene = groundAndBox();
    addDirectionalLight(scene, {0.3f, -1, 0.2f});
    for (CascadeSplitMode mode : {CascadeSplitMode::Log, CascadeSplitMode::Practical}) {
        const Settings settings = settingsWithSplits(mode);
        const ShadowFrame plan = ShadowPlanner::plan(scene, cameraLookingAt({0, 6, 15}, {0, 0, 0}), settings.shadows);
        const SplitBar bar = splitBarOf(settings, shadowPlanStats(plan));
        EXPECT_TRUE(bar.computed) << cascadeSplitModeName(mode);
        ASSERT_EQ(bar.ends.size(), plan.directional.cascades.size()) << cascadeSplitModeName(mode);
        for (size_t c = 0; c < bar.ends.size(); ++c)
            EXPECT_FLOAT_EQ(bar.ends[c], plan.directional.cascades[c].vsFar / 40.0f) << cascadeSplitModeName(mode) << " " << c;
        // Not the (ignored) ratios: log splits put the first cascade's end far nearer than ratio 0.1.
        EXPECT_NE(bar.ends[0], settings.shadows.directional.cascadeRatios[0]) << cascadeSplitModeName(mode);
        EXPECT_NEAR(bar.ends.back(), 1.0f, 1e-5f) << cascadeSplitModeName(mode);
    }
}

TEST(ViewerSplitBar, ComputedSplitsBeforeAnyFrameHaveNoSpans) {
    const SplitBar bar = splitBarOf(settingsWithSplits(CascadeSplitMode::Log), ShadowPlanStats{});
    EXPECT_TRUE(bar.computed);
    EXPECT_TRUE(bar.ends.empty());
}

TEST(ViewerStatsPanel, DroppedSunsAreTheConsideredOnesWithoutAShadowMap) {
    Scene scene = groundAndBox();
    for (int i = 0; i < 5; ++i) addDirectionalLight(scene, {0.3f, -1, 0.1f * float(i)});  // 4 are reserved at most
    EXPECT_EQ(shadowLightCounts(statsOf(scene, settingsWithSplits(CascadeSplitMode::Log))),
              "directional lights reserved 4, dropped 1; spot/point reserved 0, dropped 0");
}

TEST(ViewerCameraCombo, SceneCameraThenEachGltfCameraByName) {
    Scene scene;
    Camera named, unnamed;
    named.name = "overview";
    scene.cameras = {named, unnamed};
    EXPECT_EQ(cameraChoices(scene), (std::vector<std::string>{"scene camera", "overview", "camera 1"}));
    EXPECT_EQ(cameraChoices(Scene{}), (std::vector<std::string>{"scene camera"}));
}
