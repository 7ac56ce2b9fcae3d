// The atlas view's tile labels (src/viewer/atlas_overlay.h) from a real plan's stats JSON: each tile
// of the atlas image (the directional atlas left, the spot/point atlas right) named after its scene
// light, as --light, the inspector and the stats JSON count lights, and its cascade or cube face.
#include <gtest/gtest.h>

#include "penumbra/scene_builder.h"
#include "render/shadow_stats_json.h"
#include "shadow_test_scene.h"
#include "shadows/shadow_planner.h"
#include "spot_test_scenes.h"
#include "viewer/atlas_overlay.h"

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

// Scene lights: 0 spot, 1 point, 2 sun without shadows, 3 and 4 suns: the suns' reserved slots 0 and
// 1 are scene lights 3 and 4.
struct PlannedAtlases {
    Scene scene = test::spotGridScene(1);
    ShadowFrame plan;

    PlannedAtlases() {
        scene.lights.push_back(makePointLight({0.0f, 3.0f, 0.0f}, 50.0f, 10.0f));
        shadow_test::addDirectionalLight(scene, {0.3f, -1, 0.2f}, 1.0f, LightShadows::None);
        shadow_test::addDirectionalLight(scene, {0.3f, -1, 0.2f});
        shadow_test::addDirectionalLight(scene, {-0.2f, -1, 0.1f});
        plan = ShadowPlanner::plan(scene, resolveCameraView(scene, 128, 128), ShadowSettings{});
    }
};

void expectRect(const AtlasTileLabel& label, const AtlasTileRect& rect, glm::vec2 atlasOffset) {
    const glm::vec2 min = glm::vec2(rect.offset) + atlasOffset;
    EXPECT_EQ(label.min, min) << label.text;
    EXPECT_EQ(label.max, min + glm::vec2(float(rect.size))) << label.text;
}

}  // namespace

TEST(AtlasTileLabels, SunTilesNameTheSceneLightAndTheCascade) {
    PlannedAtlases p;
    const uint32_t cascades = uint32_t(p.plan.directional.cascades.size());
    ASSERT_EQ(p.plan.directional.lights.size(), 2u);
    ASSERT_EQ(p.plan.directional.tiles.size(), 2u * cascades);
    const std::vector<AtlasTileLabel> labels = atlasTileLabels(shadowPlanStats(p.plan), p.scene);
    ASSERT_GE(labels.size(), p.plan.directional.tiles.size());
    for (uint32_t t = 0; t < p.plan.directional.tiles.size(); ++t) {
        const uint32_t sceneLight = t < cascades ? 3 : 4;
        EXPECT_EQ(labels[t].text, "sun" + std::to_string(sceneLight) + " c" + std::to_string(t % cascades));
        expectRect(labels[t], p.plan.directional.tiles[t].rect, glm::vec2(0.0f));
    }
}

TEST(AtlasTileLabels, SpotAndPointTilesNameTheSceneLightAndTheCubeFaceRightOfTheSunAtlas) {
    PlannedAtlases p;
    ASSERT_EQ(p.plan.other.tiles.size(), 7u);  // the spot's tile, then the point light's six faces
    const std::vector<AtlasTileLabel> labels = atlasTileLabels(shadowPlanStats(p.plan), p.scene);
    const size_t first = p.plan.directional.tiles.size();
    ASSERT_EQ(labels.size(), first + 7u);
    const glm::vec2 right(float(p.plan.directional.atlas.atlasSize), 0.0f);
    const char* texts[] = {"spot0", "point1 +X", "point1 -X", "point1 +Y", "point1 -Y", "point1 +Z", "point1 -Z"};
    for (size_t t = 0; t < 7; ++t) {
        EXPECT_EQ(labels[first + t].text, texts[t]);
        expectRect(labels[first + t], spotTileViewport(p.plan.other.atlas, uint32_t(t)), right);
    }
}

TEST(AtlasTileLabels, StatsOfNoFrameGiveNoLabels) {
    PlannedAtlases p;
    EXPECT_TRUE(atlasTileLabels(ShadowPlanStats{}, p.scene).empty());
}
