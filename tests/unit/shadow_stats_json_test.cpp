// The shadow plan's stats JSON (--stats, the viewer's stats panel): atlas occupancy from the plan's
// layout, casters and triangles per tile from the GPU's counts.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/shadow_stats_json.h"
#include "shadow_test_scene.h"
#include "spot_test_scenes.h"
#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

TEST(ShadowStatsJson, OccupancyIsTheShareOfTheAtlasItsTilesTake) {
    for (uint32_t cascades = 1; cascades <= 4; ++cascades) {
        const ShadowFrame plan = groundAndBoxPlan(cascades);
        const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson(plan));
        // 1 tile fills the atlas; 2-4 tiles are quarters of a 2 x 2 split.
        const double expected = cascades == 1 ? 1.0 : 0.25 * double(cascades);
        EXPECT_DOUBLE_EQ(double(stats["directional"]["occupancy"]), expected) << cascades << " cascades";
        EXPECT_DOUBLE_EQ(double(stats["other"]["occupancy"]), 0.0) << "no spot or point light";
    }
}

TEST(ShadowStatsJson, CastersAndTrianglesPerTileAreTheGpuCounts) {
    const ShadowFrame plan = groundAndBoxPlan(2);
    ASSERT_EQ(plan.directional.tiles.size(), 2u);
    const std::vector<CullTileCount> gpu = {{3, 1200}, {5, 70000}};
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson(plan, &gpu))["directional"];
    EXPECT_EQ(stats["castersPerTile"], nlohmann::json::array({3, 5}));
    EXPECT_EQ(stats["trianglesPerTile"], nlohmann::json::array({1200, 70000}));
    EXPECT_EQ(stats["casterDraws"], 8);
}

TEST(ShadowStatsJson, WithoutGpuCountsCastersComeFromThePlanAndTrianglesAreLeftOut) {
    const ShadowFrame plan = groundAndBoxPlan(2);
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson(plan))["directional"];
    ASSERT_EQ(stats["castersPerTile"].size(), 2u);
    for (size_t tile = 0; tile < 2; ++tile)
        EXPECT_EQ(stats["castersPerTile"][tile], plan.directional.tiles[tile].casterInstances.size()) << "tile " << tile;
    EXPECT_FALSE(stats.contains("trianglesPerTile"));
}

TEST(ShadowStatsJson, SpotAtlasOccupancyCountsItsTilesOfTheSplit) {
    // 2 lights: 2 of 4 tiles; 5 lights: 5 of 9 tiles of atlasSize / 3 (rounded down); 16: all.
    for (uint32_t count : {1u, 2u, 5u, 16u}) {
        const Scene scene = test::spotGridScene(count);
        const ShadowFrame plan = ShadowPlanner::plan(scene, resolveCameraView(scene, 128, 128), ShadowSettings{});
        ASSERT_EQ(plan.other.atlas.tileCount, count);
        const double side = double(plan.other.atlas.atlasSize), third = double(plan.other.atlas.atlasSize / 3);
        const double expected = count == 2 ? 0.5 : count == 5 ? 5.0 * third * third / (side * side) : 1.0;
        const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson(plan))["other"];
        EXPECT_DOUBLE_EQ(double(stats["occupancy"]), expected) << count << " spot lights";
    }
}

TEST(ShadowStatsJson, ReservedSunsAreNamedByTheirSceneLightIndex) {
    Scene scene = baseScene();
    addBox(scene, {-20, -1, -20}, {20, 0, 20});
    addBox(scene, {-1, 0, -1}, {1, 2, 1});
    addDirectionalLight(scene, {0.3f, -1, 0.2f}, 1.0f, LightShadows::None);  // not reserved
    addDirectionalLight(scene, {0.3f, -1, 0.2f});
    addDirectionalLight(scene, {-0.2f, -1, 0.1f});
    const ShadowFrame plan = ShadowPlanner::plan(scene, cameraLookingAt({0, 6, 15}, {0, 0, 0}), sphereCascadeSettings());
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson(plan))["directional"];
    EXPECT_EQ(stats["lightsReserved"], 2);
    EXPECT_EQ(stats["reservedLights"], nlohmann::json::array({1, 2}));
}
