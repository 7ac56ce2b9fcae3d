// The frame graph's barriers under the validation layer's synchronization validation: every canonical
// scene and every path (hardware and compute shadow raster, forward and visibility main view, cached
// tiles on a second frame, clustered lights, the screen-space resolve, the tight fit, spot and point
// lights, atlas capture; the visibility buffer's compute resolve on a device made to take it) renders
// without one hazard. Small frames and atlases: the layer checks every
// command, and lavapipe runs them on the CPU.
#include <cstdio>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"

namespace penumbra::test {
namespace {

// A device of its own: synchronization validation on (the shared device has the other checks only).
Device& synchronizationDevice() {
    static std::unique_ptr<Device> device = [] {
        DeviceOptions options = testDeviceOptions();
        options.synchronizationValidation = true;
        return std::make_unique<Device>(options);
    }();
    return *device;
}

Settings smallSettings(ShadowRaster raster, MainView mainView) {
    Settings settings;
    settings.shadows.raster = raster;
    settings.render.mainView = mainView;
    settings.shadows.directional.atlasSize = 256;
    settings.shadows.spot.atlasSize = 256;
    return settings;
}

RenderRequest smallRequest() {
    RenderRequest request;
    request.width = 64;
    request.height = 36;
    return request;
}

class SynchronizationTest : public ::testing::Test {
protected:
    Device& device() { return synchronizationDevice(); }
    // Two frames (the second reuses the cached tiles) with these settings; the hazards they raised.
    uint32_t hazardsOfTwoFrames(const Scene& scene, const Settings& settings, RenderRequest request = smallRequest()) {
        const uint32_t before = device().validationMessageCount();
        Renderer renderer(device(), scene);
        renderer.render(request, settings);
        const RenderResult second = renderer.render(request, settings);
        EXPECT_GT(second.stats.tilesReused, 0u) << "the second frame draws from cached tiles";
        return device().validationMessageCount() - before;
    }
};

TEST_F(SynchronizationTest, EveryCanonicalSceneRendersWithoutHazards) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        if (info.name == "cad_engine") continue;  // 121k triangles: the same passes as the others, slower
        SCOPED_TRACE(info.name);
        EXPECT_EQ(hazardsOfTwoFrames(makeCanonicalScene(info.name), smallSettings(ShadowRaster::Hw, MainView::Forward)), 0u);
    }
}

TEST_F(SynchronizationTest, EveryRasterAndMainViewPathRendersWithoutHazards) {
    // The demo scene: a sun and a spot light; spot_lights and point_light: the other-light atlas.
    const Scene scenes[] = {makeDemoScene(), makeCanonicalScene("point_light")};
    for (const Scene& scene : scenes) {
        for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
            for (MainView mainView : {MainView::Forward, MainView::Visibility}) {
                SCOPED_TRACE(std::string(shadowRasterName(raster)) + ", " + mainViewName(mainView));
                EXPECT_EQ(hazardsOfTwoFrames(scene, smallSettings(raster, mainView)), 0u);
            }
        }
    }
}

TEST_F(SynchronizationTest, ScreenSpaceTightFitAndAtlasCaptureRenderWithoutHazards) {
    for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
        SCOPED_TRACE(shadowRasterName(raster));
        Settings settings = smallSettings(raster, MainView::Forward);
        settings.shadows.screenSpace = true;
        settings.shadows.directional.fit = CascadeFit::Tight;
        RenderRequest request = smallRequest();
        request.captureAtlas = true;
        EXPECT_EQ(hazardsOfTwoFrames(makeDemoScene(), settings, request), 0u);
    }
}

TEST_F(SynchronizationTest, LightCullingWithoutClustersAndFrustumCullingRenderWithoutHazards) {
    Settings settings = smallSettings(ShadowRaster::Compute, MainView::Visibility);
    settings.render.lightCulling = LightCulling::None;
    settings.render.viewCulling = ViewCulling::Frustum;
    EXPECT_EQ(hazardsOfTwoFrames(makeCanonicalScene("spot_lights"), settings), 0u);
}

TEST_F(SynchronizationTest, VirtualShadowMapFramesRenderWithoutHazards) {
    // Pages allocated and drawn (first frame), kept (second), invalidated by a moved caster (third),
    // on both rasterizers and both main views: marking, the table's passes, the page draws and the
    // lit pass's reads of the pool each wait for the pass before them.
    const Scene scene = makeCanonicalScene("poles");
    for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
        for (MainView mainView : {MainView::Forward, MainView::Visibility}) {
            SCOPED_TRACE(std::string(shadowRasterName(raster)) + ", " + mainViewName(mainView));
            Settings settings = smallSettings(raster, mainView);
            settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
            settings.shadows.virtualMaps.poolPages = 64;
            settings.shadows.virtualMaps.resolution = 2048;
            const uint32_t before = device().validationMessageCount();
            Renderer renderer(device(), scene);
            renderer.render(smallRequest(), settings);
            renderer.render(smallRequest(), settings);
            const uint32_t last = uint32_t(scene.instances.size()) - 1;
            renderer.setInstanceTransform(
                last, glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.0f, 0.0f)) * scene.instances[last].worldFromObject);
            const RenderResult moved = renderer.render(smallRequest(), settings);
            EXPECT_GT(moved.stats.virtualPages.drawn, 0u) << "the moved caster's pages are drawn again";
            EXPECT_EQ(device().validationMessageCount() - before, 0u);
        }
    }
}

// The visibility buffer's compute resolve, GPUs' path (gpu::DeviceFaultInjection::computeResolve makes
// lavapipe take it): the resolve's colour image copied into the target, the view's depth copied only
// for the blended draws after it (the demo scene has one), the gradient background, virtual faces.
// Directional lights take cascades here: Mesa 22.3's lavapipe corrupts its heap now and then running the
// shading functions in a compute shader (render/visibility_pass.h, why CPU devices resolve in fragments),
// in about 2 runs of 5 with the directional virtual lookup compiled in (with or without synchronization
// validation), in none of 25 with cascades and virtual faces.
TEST(SynchronizationComputeResolve, TheComputeResolveRendersWithoutHazards) {
    DeviceOptions options = testDeviceOptions();
    options.synchronizationValidation = true;
    gpu::DeviceFaultInjection faults;
    faults.computeResolve = true;
    Device device = DeviceAccess::makeDevice({options, faults});
    Settings settings = smallSettings(ShadowRaster::Compute, MainView::Visibility);
    settings.render.background = Background::Gradient;
    settings.shadows.directional.mode = DirectionalShadowMode::Cascades;
    settings.shadows.spot.mode = SpotShadowMode::Virtual;
    for (const Scene& scene : {makeDemoScene(), makeCanonicalScene("poles")}) {
        Renderer renderer(device, scene);
        for (int frame = 0; frame < 2; ++frame) {
            const RenderResult result = renderer.render(smallRequest(), settings);
            EXPECT_EQ(result.stats.mainView, "visibility");
        }
    }
    EXPECT_EQ(device.validationMessageCount(), 0u);
}

TEST_F(SynchronizationTest, VirtualFaceFramesRenderWithoutHazards) {
    // The same for spot and point lights' faces (a point light's six and a spot light's one, with a sun's
    // virtual map in the same frames: two tables, two pools, one marking depth).
    Scene scene = makeCanonicalScene("room_corner");
    const Scene spots = makeCanonicalScene("spot_lights");
    scene.lights.insert(scene.lights.end(), spots.lights.begin(), spots.lights.end());
    for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
        for (MainView mainView : {MainView::Forward, MainView::Visibility}) {
            SCOPED_TRACE(std::string(shadowRasterName(raster)) + ", " + mainViewName(mainView));
            Settings settings = smallSettings(raster, mainView);
            settings.shadows.spot.mode = SpotShadowMode::Virtual;
            settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
            settings.shadows.virtualMaps.poolPages = 64;
            settings.shadows.virtualMaps.facePoolPages = 64;
            settings.shadows.virtualMaps.resolution = 2048;
            settings.shadows.virtualMaps.faceResolution = 2048;
            const uint32_t before = device().validationMessageCount();
            Renderer renderer(device(), scene);
            const RenderResult first = renderer.render(smallRequest(), settings);
            renderer.render(smallRequest(), settings);
            const uint32_t last = uint32_t(scene.instances.size()) - 1;
            renderer.setInstanceTransform(
                last, glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 0.0f, 0.0f)) * scene.instances[last].worldFromObject);
            renderer.render(smallRequest(), settings);
            EXPECT_GE(first.stats.virtualFacePages.maps, 7u) << "the point light's six faces and a spot's";
            EXPECT_GT(first.stats.virtualFacePages.drawn, 0u);
            EXPECT_EQ(device().validationMessageCount() - before, 0u);
        }
    }
}

}  // namespace
}  // namespace penumbra::test
