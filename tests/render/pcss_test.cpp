// Contact-hardening soft shadows (PCSS, Fernando 2005): lights with shadows "pcss" against the ray-traced
// area-light reference (penumbra reference --soft): the penumbra is as wide as the truth's, within 20 %.
#include <cstdio>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 320, kHeight = 180;

// Valid pixels strictly between 10 % and 90 % lit: the penumbra's area.
uint64_t penumbraPixels(const Image& image, const Image& validMask) {
    uint64_t count = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        count += validMask.pixels[i] != 0 && image.pixels[i] > 25 && image.pixels[i] < 230 ? 1 : 0;
    return count;
}

}  // namespace

TEST_F(CompareTest, PcssPenumbraIsAsWideAsTheAreaLightsWithin20Percent) {
    const Scene& scene = canonicalScene("pcss_contact");
    const CameraView view = resolveCameraView(scene, kWidth, kHeight);
    Renderer renderer(device(), scene);
    for (uint32_t light : {0u, 1u}) {  // a 3° sun, a spot with a 15 cm emitter
        const Settings settings;
        ReferenceOptions options = referenceOptionsFor(settings, view);
        options.softSamples = 128;
        const ReferenceImages truth = traceReferenceShadow(scene, view, light, false, options);
        const Image ours = renderer.render({kWidth, kHeight, OutputMode::ShadowAov, light, false}, settings, view).image;
        const double truthWidth = double(penumbraPixels(truth.shadow, truth.validMask));
        const double ourWidth = double(penumbraPixels(ours, truth.validMask));
        const CompareMetrics m = compareShadowImages(ours, truth.shadow, truth.validMask);
        std::printf("[pcss] light %u: penumbra %.0f px (truth %.0f), misclassified %.3f %%, MAE %.4f\n", light, ourWidth,
                    truthWidth, m.misclassifiedPercent, m.meanAbsoluteError);
        EXPECT_GT(truthWidth, 200.0) << "the scene should have wide penumbrae";
        EXPECT_NEAR(ourWidth / truthWidth, 1.0, 0.2) << "light " << light;
        EXPECT_LE(m.interiorMisclassifiedPercent, 0.01) << "light " << light;
    }
}
