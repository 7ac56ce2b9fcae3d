// The viewer's reference comparison (src/viewer/reference_view.h) without a window: cube.gltf traced
// on the worker thread at a small size, against a hand-made "ours" that is wrong on purpose, so the
// picture must be penumbra compare's (makeDiffImage) with red and cyan where expected.
#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/camera.h"
#include "penumbra/scene_loading.h"
#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"
#include "viewer/reference_view.h"

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

const std::string kCube = std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/cube.gltf";
constexpr uint32_t kWidth = 64, kHeight = 36;

// The reference made wrong everywhere: lit where it is shadowed and the other way round.
Image wrongShadow(const Image& reference) {
    Image ours = reference;
    for (uint8_t& value : ours.pixels) value = uint8_t(255 - value);
    return ours;
}

struct CubeJob {
    Scene scene = loadScene(kCube);
    CameraView view = resolveCameraView(scene, kWidth, kHeight);
    Settings settings;
    ReferenceImages reference = traceReferenceShadow(scene, view, 0, false, referenceOptionsFor(settings, view, 0));
    ReferenceJob job() const {
        return ReferenceJob{scene, view, 0, referenceOptionsFor(settings, view, 0), wrongShadow(reference.shadow),
                            Image(kWidth, kHeight, 3, 200)};
    }
    ReferenceKey key() const { return referenceKeyOf(view, 0, settings); }
};

size_t countColour(const Image& image, uint8_t r, uint8_t g, uint8_t b) {
    size_t n = 0;
    for (size_t p = 0; p < image.pixels.size(); p += 3)
        n += image.pixels[p] == r && image.pixels[p + 1] == g && image.pixels[p + 2] == b;
    return n;
}

}  // namespace

TEST(ReferenceView, TracesOnAWorkerAndDrawsPenumbraComparesPicture) {
    const CubeJob cube;
    const ReferenceJob job = cube.job();
    ReferenceComparison comparison;
    comparison.start(job, cube.key());
    EXPECT_EQ(comparison.wait(), ReferenceComparison::State::Ready) << comparison.error();
    EXPECT_FLOAT_EQ(comparison.progress(), 1.0f);
    const Image expected = makeDiffImage(job.colour, job.oursShadow, cube.reference.shadow, cube.reference.validMask);
    ASSERT_EQ(comparison.diff().pixels.size(), expected.pixels.size());
    EXPECT_TRUE(comparison.diff().pixels == expected.pixels) << "not penumbra compare's picture";
    const CompareMetrics metrics = compareShadowImages(job.oursShadow, cube.reference.shadow, cube.reference.validMask);
    EXPECT_EQ(comparison.metrics().falseLit, metrics.falseLit);
    EXPECT_EQ(comparison.metrics().falseShadow, metrics.falseShadow);
    // Every valid pixel is wrong: false lit (cyan) in the reference's shadow, false shadow (red) elsewhere.
    EXPECT_GT(countColour(comparison.diff(), 0, 255, 255), 0u);
    EXPECT_GT(countColour(comparison.diff(), 255, 0, 0), 0u);
    EXPECT_EQ(countColour(comparison.diff(), 0, 255, 255), metrics.falseLit);
    EXPECT_EQ(countColour(comparison.diff(), 255, 0, 0), metrics.falseShadow);
}

TEST(ReferenceView, RightShadowGivesNoDisagreementColours) {
    const CubeJob cube;
    ReferenceJob job = cube.job();
    job.oursShadow = cube.reference.shadow;
    ReferenceComparison comparison;
    comparison.start(job, cube.key());
    ASSERT_EQ(comparison.wait(), ReferenceComparison::State::Ready);
    EXPECT_EQ(countColour(comparison.diff(), 0, 255, 255), 0u);
    EXPECT_EQ(countColour(comparison.diff(), 255, 0, 0), 0u);
    EXPECT_GT(countColour(comparison.diff(), 100, 100, 100), 0u) << "valid pixels: the base dimmed to 50 %";
}

TEST(ReferenceView, AnotherCameraLightSizeOrSettingsDropsIt) {
    const CubeJob cube;
    ReferenceComparison comparison;
    comparison.start(cube.job(), cube.key());
    comparison.wait();
    comparison.keepOnlyFor(cube.key());
    EXPECT_EQ(comparison.state(), ReferenceComparison::State::Ready) << "the same key keeps it";
    const CameraView moved = translatedCameraView(cube.view, glm::vec3(0.01f, 0.0f, 0.0f));
    Settings other = cube.settings;
    other.shadows.maxDistance = 50.0f;
    for (const ReferenceKey& key : {referenceKeyOf(moved, 0, cube.settings), referenceKeyOf(cube.view, 1, cube.settings),
                                    referenceKeyOf(resolveCameraView(cube.scene, kWidth, kHeight + 1), 0, cube.settings),
                                    referenceKeyOf(cube.view, 0, other)}) {
        ReferenceComparison dropped;
        dropped.start(cube.job(), cube.key());
        dropped.keepOnlyFor(key);  // while tracing or after: either way it goes
        EXPECT_EQ(dropped.state(), ReferenceComparison::State::None);
        EXPECT_TRUE(dropped.diff().empty());
    }
}

TEST(ReferenceView, LightWithoutShadowsFailsWithTheTracersMessage) {
    CubeJob cube;
    ReferenceJob job = cube.job();
    job.scene.lights[0].shadows = LightShadows::None;
    ReferenceComparison comparison;
    comparison.start(job, cube.key());
    EXPECT_EQ(comparison.wait(), ReferenceComparison::State::Failed);
    EXPECT_NE(comparison.error().find("light 0"), std::string::npos) << comparison.error();
}

TEST(ReferenceView, TracerCountsRowsAndStopsWhenCancelled) {
    const Scene scene = loadScene(kCube);
    const CameraView view = resolveCameraView(scene, kWidth, kHeight);
    std::atomic<uint32_t> rows{0};
    std::atomic<bool> cancel{false};
    ReferenceOptions options;
    options.rowsDone = &rows;
    options.cancel = &cancel;
    const ReferenceImages full = traceReferenceShadow(scene, view, 0, false, options);
    EXPECT_EQ(rows.load(), kHeight);
    EXPECT_GT(full.validPixels, 0u);
    rows = 0;
    cancel = true;
    const ReferenceImages cancelled = traceReferenceShadow(scene, view, 0, false, options);
    EXPECT_EQ(rows.load(), kHeight) << "skipped rows count as done";
    EXPECT_EQ(cancelled.validPixels, 0u) << "a cancelled trace traced nothing";
}
