// GPU culling of the visibility-buffer main view (render.viewCulling): the shadow
// culling pass's camera lists cull by the frustum and, in two phases, by a depth pyramid of what the
// early phase drew. Culling changes what is drawn, never the image: culled and unculled frames are
// compared pixel for pixel (the visibility buffer keeps the nearest surface by an atomic maximum,
// whatever the order, so the tolerance is exact equality).
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"

namespace penumbra::test {
namespace {

constexpr uint32_t kShown = 3, kHiddenBoxes = 25, kBoxesBehindTheCamera = 3;

// A wall across the view (y -3 .. 3) at z = -5 hides a 5 x 5 grid of boxes at z = -15 (y -4.5 .. 4.5:
// the wall's top edge is at y = 6.15 there as the camera sees it); a box behind the wall peeks out
// over it (y 6 .. 7), one box stands in front of it, so three instances show (the wall too); three
// boxes are behind the camera (at z = +20, the camera at z = 5 looks to -z).
Scene wallScene() {
    SceneBuilder builder;
    Material grey;
    grey.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
    const uint32_t material = builder.addMaterial(grey);
    const uint32_t wall = builder.addMesh(makeBoxMesh({40.0f, 3.0f, 0.25f}, material));
    const uint32_t box = builder.addMesh(makeBoxMesh({0.5f, 0.5f, 0.5f}, material));
    builder.addInstance(wall, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -5.0f}));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {1.0f, 1.0f, -1.0f}));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {0.0f, 6.5f, -15.0f}));  // peeks out over the wall
    for (uint32_t i = 0; i < kHiddenBoxes; ++i)
        builder.addInstance(box, glm::translate(glm::mat4(1.0f), {float(i % 5) * 2.0f - 4.0f, float(i / 5) * 2.0f - 4.0f, -15.0f}));
    for (uint32_t i = 0; i < kBoxesBehindTheCamera; ++i)
        builder.addInstance(box, glm::translate(glm::mat4(1.0f), {float(i) * 2.0f - 2.0f, 0.0f, 20.0f}));
    builder.addLight(makeDirectionalLight({-0.3f, -1.0f, -0.4f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -10.0f}, 1.0f));
    return builder.build();
}

class ViewCullingTest : public RenderTest {
protected:
    static Settings settingsFor(ViewCulling culling) {
        Settings settings;
        settings.render.mainView = MainView::Visibility;
        settings.render.viewCulling = culling;
        settings.shadows.directional.atlasSize = 512;  // lavapipe: keep the shadow passes small
        settings.shadows.spot.atlasSize = 512;
        return settings;
    }
    static RenderRequest smallRequest() {
        RenderRequest request;
        request.width = 192;
        request.height = 108;
        return request;
    }
    // `frames` frames of `culling` from `view`; the last one's result.
    static RenderResult renderFrames(Renderer& renderer, ViewCulling culling, const CameraView& view, int frames) {
        RenderResult result;
        for (int i = 0; i < frames; ++i) result = renderer.render(smallRequest(), settingsFor(culling), view);
        return result;
    }
    static CameraView frontView(const Scene& scene) { return resolveCameraView(scene, 192, 108); }
    // Just behind the wall (its back face at z = -5.25), looking at the whole grid of boxes it hid.
    static CameraView behindTheWallView() {
        return makeCameraView(makeLookAtCamera({0.0f, 0.0f, -5.6f}, {0.0f, 0.0f, -15.0f}, 1.0f), 192, 108);
    }
};

TEST_F(ViewCullingTest, FrustumCullingSkipsTheInstancesBehindTheCamera) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    const RenderResult frame = renderFrames(renderer, ViewCulling::Frustum, frontView(scene), 1);
    EXPECT_EQ(frame.stats.viewInstances, kShown + kHiddenBoxes + kBoxesBehindTheCamera);
    EXPECT_EQ(frame.stats.viewInstancesEarly, kShown + kHiddenBoxes);
    EXPECT_EQ(frame.stats.viewInstancesLate, 0u);
    const RenderResult unculled = renderFrames(renderer, ViewCulling::None, frontView(scene), 1);
    EXPECT_EQ(shareOfPixelsOver(frame.image, unculled.image, 0), 0.0);
}

TEST_F(ViewCullingTest, AMaterialTurnedBlendedTakesItsInstancesOutOfTheVisibilityBuffer) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    EXPECT_EQ(renderFrames(renderer, ViewCulling::Frustum, frontView(scene), 1).stats.viewInstances,
              kShown + kHiddenBoxes + kBoxesBehindTheCamera);
    Material blended = scene.materials[0];  // every instance's
    blended.alphaMode = AlphaMode::Blend;
    blended.baseColorFactor.a = 0.5f;
    renderer.setMaterial(0, blended);
    EXPECT_EQ(renderFrames(renderer, ViewCulling::Frustum, frontView(scene), 1).stats.viewInstances, 0u)
        << "blended materials are drawn forward, after the visibility buffer";
}

TEST_F(ViewCullingTest, NoCullingDrawsEveryInstance) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    const RenderResult frame = renderFrames(renderer, ViewCulling::None, frontView(scene), 1);
    EXPECT_EQ(frame.stats.viewInstancesEarly, kShown + kHiddenBoxes + kBoxesBehindTheCamera);
    EXPECT_EQ(frame.stats.viewInstancesLate, 0u);
}

TEST_F(ViewCullingTest, OcclusionCullingDrawsOnlyWhatTheWallLeavesVisibleOnceItsHistorySettles) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    // Frame 1: nothing was visible before, so the late phase (against an empty pyramid) draws the
    // frustum; frame 2 draws those early and finds the hidden ones behind the wall; frame 3 draws
    // the three that show only (the box peeking out over the wall among them: the pyramid keeps the
    // farthest depth of each region, the sky beside the wall's edge).
    const RenderResult first = renderFrames(renderer, ViewCulling::Occlusion, frontView(scene), 1);
    EXPECT_EQ(first.stats.viewInstancesEarly, 0u);
    EXPECT_EQ(first.stats.viewInstancesLate, kShown + kHiddenBoxes);
    const RenderResult third = renderFrames(renderer, ViewCulling::Occlusion, frontView(scene), 2);
    EXPECT_EQ(third.stats.viewInstancesEarly, kShown);
    EXPECT_EQ(third.stats.viewInstancesLate, 0u);
    const RenderResult unculled = renderFrames(renderer, ViewCulling::None, frontView(scene), 1);
    EXPECT_EQ(shareOfPixelsOver(third.image, unculled.image, 0), 0.0);
    EXPECT_GT(third.stats.viewTriangles, 0u);
    EXPECT_LT(third.stats.viewTriangles, unculled.stats.viewTriangles);
}

TEST_F(ViewCullingTest, InstancesUncoveredByACameraMoveAreDrawnInThatFrame) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    renderFrames(renderer, ViewCulling::Occlusion, frontView(scene), 3);  // the history: the three shown
    const RenderResult moved = renderFrames(renderer, ViewCulling::Occlusion, behindTheWallView(), 1);
    EXPECT_EQ(moved.stats.viewInstancesEarly, 0u) << "the three shown are behind the camera or above the view now";
    EXPECT_EQ(moved.stats.viewInstancesLate, kHiddenBoxes) << "the late phase finds the boxes the wall hid";
    const RenderResult unculled = renderFrames(renderer, ViewCulling::None, behindTheWallView(), 1);
    EXPECT_EQ(shareOfPixelsOver(moved.image, unculled.image, 0), 0.0);
}

TEST_F(ViewCullingTest, CulledImagesEqualUnculledOnEveryCanonicalScene) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        Renderer renderer(device(), scene);
        const CameraView view = frontView(scene);
        const RenderResult unculled = renderFrames(renderer, ViewCulling::None, view, 1);
        // Frame 2 draws frame 1's frustum early (its pyramid was empty); frame 3's early phase draws
        // what frame 2's pyramid found visible.
        const RenderResult occlusion = renderFrames(renderer, ViewCulling::Occlusion, view, 3);
        EXPECT_EQ(shareOfPixelsOver(unculled.image, occlusion.image, 0), 0.0) << info.name;
        EXPECT_LE(occlusion.stats.viewInstancesEarly + occlusion.stats.viewInstancesLate,
                  unculled.stats.viewInstancesEarly)
            << info.name;
    }
}

TEST_F(ViewCullingTest, TheForwardPassReportsNoViewCulling) {
    const Scene scene = wallScene();
    Renderer renderer(device(), scene);
    Settings settings = settingsFor(ViewCulling::Occlusion);
    settings.render.mainView = MainView::Forward;
    const RenderResult frame = renderer.render(smallRequest(), settings, frontView(scene));
    EXPECT_EQ(frame.stats.viewInstances, 0u);
    EXPECT_EQ(frame.stats.viewInstancesEarly + frame.stats.viewInstancesLate, 0u);
}

}  // namespace
}  // namespace penumbra::test
