// Cached shadow tiles (shadows.cacheTiles): a still frame draws no tile and looks the same; a moving
// camera keeps the spot tiles; a moved caster draws its tiles again.
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "spot_render_scenes.h"

namespace penumbra::test {
namespace {

class CachedTilesTest : public RenderTest, public ::testing::WithParamInterface<ShadowRaster> {
protected:
    Settings settings(bool cache) const {
        Settings s;
        s.shadows.raster = GetParam();
        s.shadows.cacheTiles = cache;
        s.shadows.directional.atlasSize = 512;
        s.shadows.spot.atlasSize = 512;
        return s;
    }
    static RenderRequest aov(uint32_t light) {
        RenderRequest request;
        request.width = 96;
        request.height = 54;
        request.output = OutputMode::ShadowAov;
        request.aovLight = light;
        return request;
    }
};

TEST_P(CachedTilesTest, StillFrameDrawsNoTileAndLooksTheSame) {
    Renderer renderer(device(), makeDemoScene());
    const RenderResult first = renderer.render(aov(0), settings(true));
    EXPECT_GT(first.stats.tilesRendered, 0u);
    const RenderResult second = renderer.render(aov(0), settings(true));
    EXPECT_EQ(second.stats.tilesRendered, 0u);
    EXPECT_EQ(second.stats.tilesReused, first.stats.tilesRendered);
    EXPECT_TRUE(second.image.pixels == first.image.pixels);
    const RenderResult spots = renderer.render(aov(1), settings(true));  // the spot's tiles, kept too
    Renderer uncached(device(), makeDemoScene());
    EXPECT_TRUE(spots.image.pixels == uncached.render(aov(1), settings(false)).image.pixels);
}

TEST_P(CachedTilesTest, MovingCameraKeepsTheSpotTilesAndRedrawsTheCascades) {
    Renderer cached(device(), makeDemoScene()), uncached(device(), makeDemoScene());
    const CameraView start = resolveCameraView(cached.scene(), 96, 54);
    for (int step = 0; step < 3; ++step) {
        Camera camera;
        camera.worldFromView = glm::translate(glm::mat4(1.0f), glm::vec3(0.7f * float(step), 0, 0)) * start.worldFromView;
        camera.yfov = start.yfov;
        camera.zNear = start.zNear;
        camera.zFar = start.zFar;
        const CameraView view = makeCameraView(camera, 96, 54);
        for (uint32_t light : {0u, 1u}) {
            const RenderResult a = cached.render(aov(light), settings(true), view);
            const RenderResult b = uncached.render(aov(light), settings(false), view);
            EXPECT_TRUE(a.image.pixels == b.image.pixels) << "step " << step << " light " << light;
            if (step > 0 && light == 0) {
                EXPECT_GE(a.stats.tilesRendered, 1u) << "the cascades follow the camera";
                EXPECT_GE(a.stats.tilesReused, 2u) << "the two spots' tiles stay";
            }
        }
    }
}

TEST_P(CachedTilesTest, MovedCasterDrawsItsTilesAgain) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    Renderer renderer(device(), scene);
    renderer.render(aov(0), settings(true));
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.5f, 0.4f));
    renderer.setInstanceTransform(1, moved);
    const RenderResult after = renderer.render(aov(0), settings(true));
    EXPECT_EQ(after.stats.tilesReused, 0u);
    scene.instances[1].worldFromObject = moved;
    scene.instances[1].wsBounds = scene.meshes[scene.instances[1].meshIndex].osBounds.transformed(moved);
    Renderer fresh(device(), scene);
    EXPECT_TRUE(after.image.pixels == fresh.render(aov(0), settings(false)).image.pixels);
}

INSTANTIATE_TEST_SUITE_P(BothRasterizers, CachedTilesTest, ::testing::Values(ShadowRaster::Hw, ShadowRaster::Compute),
                         [](const auto& info) { return std::string(shadowRasterName(info.param)); });

}  // namespace
}  // namespace penumbra::test
