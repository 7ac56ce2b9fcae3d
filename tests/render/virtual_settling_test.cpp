// Settled frames (render/virtual_settling.h): once a frame finds every page it needs resident, the
// frames of the same inputs skip the virtual maps' page update (no marking, table or drawing pass) and
// give the same image; a moved camera, an edited caster or a turned light update the pages again.
// Lavapipe, 256x144, validation on (any message fails).
#include <algorithm>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

Settings directionalVirtual() {
    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    return settings;
}

Settings facesVirtual() {
    Settings settings;
    settings.shadows.spot.mode = SpotShadowMode::Virtual;
    return settings;
}

bool hasTiming(const RenderResult& result, const std::string& name) {
    const std::vector<PassTiming>& timings = result.stats.gpuTimings;
    return std::any_of(timings.begin(), timings.end(), [&](const PassTiming& t) { return t.name == name; });
}

class VirtualSettlingTest : public CompareTest {
protected:
    // Three frames of one view: the first draws, the second finds every page resident, the third is settled.
    std::vector<RenderResult> threeStillFrames(Renderer& renderer, const Settings& settings, const CameraView& view) {
        std::vector<RenderResult> frames;
        for (int i = 0; i < 3; ++i) frames.push_back(renderAov(renderer, settings, view));
        return frames;
    }
};

}  // namespace

TEST_F(VirtualSettlingTest, AStillCameraSkipsThePageUpdateOnceAFrameFindsEveryPageResident) {
    const Scene& scene = canonicalScene("poles");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    const std::vector<RenderResult> frames = threeStillFrames(renderer, directionalVirtual(), view);
    const VirtualPageCounts& atRest = frames[1].stats.virtualPages;
    const VirtualPageCounts& settled = frames[2].stats.virtualPages;
    EXPECT_FALSE(atRest.settled);
    EXPECT_TRUE(hasTiming(frames[1], "virtualPages/mark"));
    EXPECT_TRUE(settled.settled);
    EXPECT_FALSE(hasTiming(frames[2], "virtualPages/mark")) << "no marking pass";
    EXPECT_FALSE(hasTiming(frames[2], "virtualPages/table")) << "no page-table pass";
    EXPECT_TRUE(hasTiming(frames[2], "shadows.virtual")) << "the step's timer stays, empty";
    EXPECT_EQ(settled.requested, atRest.requested);
    EXPECT_EQ(settled.cached, settled.requested);
    EXPECT_EQ(settled.drawn, 0u);
    EXPECT_EQ(frames[2].image.pixels, frames[1].image.pixels);
}

TEST_F(VirtualSettlingTest, SpotAndPointFacesSettleLikeTheDirectionalMaps) {
    const Scene& scene = canonicalScene("point_light");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    const std::vector<RenderResult> frames = threeStillFrames(renderer, facesVirtual(), view);
    EXPECT_FALSE(frames[1].stats.virtualFacePages.settled);
    EXPECT_TRUE(frames[2].stats.virtualFacePages.settled);
    EXPECT_FALSE(hasTiming(frames[2], "virtualFaces/mark"));
    EXPECT_EQ(frames[2].stats.virtualFacePages.requested, frames[1].stats.virtualFacePages.requested);
    EXPECT_EQ(frames[2].image.pixels, frames[1].image.pixels);
}

// After settling, a camera 30 cm to the side updates the pages again: its image is a fresh renderer's.
TEST_F(VirtualSettlingTest, AMovedCameraUpdatesThePagesAgain) {
    const Scene& scene = canonicalScene("poles");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    const CameraView moved = translatedCameraView(view, wsCameraRight(view) * 0.3f);
    Renderer renderer(device(), scene);
    threeStillFrames(renderer, directionalVirtual(), view);
    const RenderResult after = renderAov(renderer, directionalVirtual(), moved);
    EXPECT_FALSE(after.stats.virtualPages.settled);
    EXPECT_TRUE(hasTiming(after, "virtualPages/mark"));
    Renderer fresh(device(), scene);
    EXPECT_EQ(after.image.pixels, renderAov(fresh, directionalVirtual(), moved).image.pixels);
}

TEST_F(VirtualSettlingTest, AMovedCasterEndsTheSettledFrames) {
    const Scene& scene = canonicalScene("poles");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    threeStillFrames(renderer, directionalVirtual(), view);
    renderer.setInstanceTransform(1, glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, 0.0f)) *
                                         scene.instances[1].worldFromObject);  // pole_0
    const RenderResult after = renderAov(renderer, directionalVirtual(), view);
    EXPECT_FALSE(after.stats.virtualPages.settled);
    EXPECT_GT(after.stats.virtualPages.drawn, 0u);
}

TEST_F(VirtualSettlingTest, ATurnedLightEndsTheSettledFrames) {
    const Scene& scene = canonicalScene("poles");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    threeStillFrames(renderer, directionalVirtual(), view);
    Light turned = scene.lights[0];
    turned.wsDirection = glm::normalize(turned.wsDirection + glm::vec3(0.1f, 0.0f, 0.05f));
    renderer.setLight(0, turned);
    const RenderResult after = renderAov(renderer, directionalVirtual(), view);
    EXPECT_FALSE(after.stats.virtualPages.settled);
    EXPECT_EQ(after.stats.virtualPages.drawn, after.stats.virtualPages.requested);
}
