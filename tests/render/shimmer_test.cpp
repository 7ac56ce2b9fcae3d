// Stable cascades under motion: moving the camera sideways in 2 cm steps over the
// far-field scene must not flip shadow pixels where the truth does not change. Away from the truth's
// shadow edges no pixel may flip at all (the shadow map's texels stay put in the world: snapped sphere
// centres, a radius independent of the camera's orientation, exact per-texel compares); on the edges
// the flips are bounded by how far our edges sit from the true ones. The tight fit (boxes quantized
// to 1/8 octave, snapped to texels) must be as stable.
#include <cstdio>
#include <utility>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Frame {
    Image ours;
    ReferenceImages reference;
};

Frame renderFrame(Renderer& renderer, const Scene& scene, const CameraView& view, const Settings& settings) {
    RenderRequest request{view.width, view.height, OutputMode::ShadowAov, 0, false};
    Frame frame;
    frame.ours = renderer.render(request, settings, view).image;
    frame.reference = traceReferenceShadow(scene, view, 0, false, referenceOptionsFor(settings, view));
    return frame;
}

}  // namespace

TEST_F(CompareTest, FarFieldShadowsDoNotShimmerWhenTheCameraSteps2cmSideways) {
    const Scene& scene = canonicalScene("far_field");
    const CameraView start = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    for (const auto& [fit, filter] : {std::pair{CascadeFit::Sphere, ShadowFilter::PCF2x2},
                                       std::pair{CascadeFit::Sphere, ShadowFilter::PCF5x5},
                                       std::pair{CascadeFit::Tight, ShadowFilter::PCF2x2}}) {
        SCOPED_TRACE(cascadeFitName(fit));
        Settings settings;
        settings.shadows.maxDistance = 150.0f;
        settings.shadows.directional.filter = filter;
        settings.shadows.directional.fit = fit;
        Frame previous = renderFrame(renderer, scene, start, settings);
        uint64_t flickering = 0, pixels = 0;
        for (int step = 1; step <= 4; ++step) {
            const CameraView view = translatedCameraView(start, 0.02f * float(step) * wsCameraRight(start));
            Frame next = renderFrame(renderer, scene, view, settings);
            const ShimmerMetrics s = compareShimmer(previous.ours, next.ours, previous.reference.shadow,
                                                    next.reference.shadow, previous.reference.validMask,
                                                    next.reference.validMask);
            std::printf("[shimmer] %s step %d: %.3f %% (interior %.3f %%, truth flips %llu)\n", shadowFilterName(filter),
                        step, s.shimmerPercent, s.interiorShimmerPercent, (unsigned long long)s.referenceFlips);
            EXPECT_EQ(s.interiorFlickering, 0u) << shadowFilterName(filter) << " step " << step;
            EXPECT_GT(s.referenceFlips, 0u) << "the truth's edges move: the step is big enough to matter";
            flickering += s.flickering;
            pixels += s.pixels;
            previous = std::move(next);
        }
        // Measured 0.06-0.09 % per step (edge pixels only).
        EXPECT_LT(100.0 * double(flickering) / double(pixels), 0.15) << shadowFilterName(filter);
    }
}

// Virtual shadow maps (shadows.directional.mode = virtual): every level's texel grid is fixed in the
// light's space and the level a pixel reads depends only on its distance, so a camera walking 8 steps of
// 2 cm flips no pixel away from the truth's edges, on the far field, under a low sun and on the CAD model.
TEST_F(CompareTest, VirtualShadowsDoNotShimmerAlongAPathOf8Steps) {
    // The most % of pixels (all of them on edges) that may flip in ours only, over the 8 steps; measured
    // 0.014, 0.045 and 0.011 (the cascades above: 0.06-0.09 % per step on the far field).
    const struct {
        const char* scene;
        double limit;
    } cases[] = {{"far_field", 0.025}, {"low_sun", 0.07}, {"cad_engine", 0.02}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.scene);
        const Scene& scene = canonicalScene(c.scene);
        const CameraView start = resolveCameraView(scene, kCompareWidth, kCompareHeight);
        Renderer renderer(device(), scene);
        Settings settings;
        settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
        if (std::string(c.scene) == "far_field") settings.shadows.maxDistance = 150.0f;
        Frame previous = renderFrame(renderer, scene, start, settings);
        uint64_t flickering = 0, pixels = 0;
        for (int step = 1; step <= 8; ++step) {
            const CameraView view = translatedCameraView(start, 0.02f * float(step) * wsCameraRight(start));
            Frame next = renderFrame(renderer, scene, view, settings);
            const ShimmerMetrics s = compareShimmer(previous.ours, next.ours, previous.reference.shadow,
                                                    next.reference.shadow, previous.reference.validMask,
                                                    next.reference.validMask);
            std::printf("[shimmer] virtual %s step %d: %.3f %% (interior %.3f %%, truth flips %llu)\n", c.scene, step,
                        s.shimmerPercent, s.interiorShimmerPercent, (unsigned long long)s.referenceFlips);
            EXPECT_EQ(s.interiorFlickering, 0u) << "step " << step;
            flickering += s.flickering;
            pixels += s.pixels;
            previous = std::move(next);
        }
        EXPECT_LT(100.0 * double(flickering) / double(pixels), c.limit);
    }
}
