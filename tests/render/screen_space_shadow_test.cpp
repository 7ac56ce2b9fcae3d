// The URP-style screen-space shadow resolve (shadows.screenSpace) gives the forward path's
// image: same shadow AOV and same colour, up to the rounding of the reconstructed position and normal.
#include <cstdio>
#include <cstdlib>

#include "directional_shadow_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 160;

struct ImageDiff {
    int maxAbs = 0;
    double withinPercent = 0.0;  // of samples differing by at most the tolerance
};

ImageDiff diff(const Image& a, const Image& b, int tolerance) {
    ImageDiff d;
    size_t within = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const int delta = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
        d.maxAbs = std::max(d.maxAbs, delta);
        within += delta <= tolerance;
    }
    d.withinPercent = 100.0 * double(within) / double(a.pixels.size());
    return d;
}

class ScreenSpaceShadowTest : public DirectionalShadowTest {
protected:
    // Renders `output` with the forward path and with the screen-space resolve and compares them.
    ImageDiff compareForwardAndScreenSpace(Settings settings, OutputMode output, const char* what) {
        const Scene scene = boxesInDepthScene();
        const RenderRequest request{kSize, kSize, output, 0, false};
        settings.shadows.screenSpace = false;
        const Image forward = renderScene(scene, request, settings).image;
        settings.shadows.screenSpace = true;
        const RenderResult resolved = renderScene(scene, request, settings);
        const Image& screenSpace = resolved.image;
        const auto& timings = resolved.stats.gpuTimings;
        EXPECT_TRUE(std::any_of(timings.begin(), timings.end(), [](const auto& t) { return t.name == "screenSpaceShadows"; }))
            << "the resolve pass did not run";
        EXPECT_EQ(forward.channels, screenSpace.channels);
        const ImageDiff d = diff(forward, screenSpace, 1);
        std::printf("[screen-space] %-28s max |diff| %d, %.3f %% of samples within 1 level\n", what, d.maxAbs,
                    d.withinPercent);
        return d;
    }
};

}  // namespace

TEST_F(ScreenSpaceShadowTest, ResolvedShadowAovEqualsTheForwardPath) {
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF7x7}) {
        const Settings settings = shadowSettings(40.0f, 4, 1024, filter);
        const ImageDiff d = compareForwardAndScreenSpace(settings, OutputMode::ShadowAov, shadowFilterName(filter));
        EXPECT_GE(d.withinPercent, 99.9) << shadowFilterName(filter);
    }
}

TEST_F(ScreenSpaceShadowTest, ResolvedColourImageEqualsTheForwardPath) {
    const ImageDiff d = compareForwardAndScreenSpace(shadowSettings(40.0f), OutputMode::Color, "colour PCF2x2");
    EXPECT_GE(d.withinPercent, 99.9);
}

TEST_F(ScreenSpaceShadowTest, ResolveWithSoftAndDitherBlendEqualsTheForwardPath) {
    for (CascadeBlend blend : {CascadeBlend::Soft, CascadeBlend::Dither}) {
        Settings settings = shadowSettings(40.0f, 4, 1024, ShadowFilter::PCF3x3, blend);
        settings.shadows.directional.cascadeFade = 0.3f;
        const ImageDiff d = compareForwardAndScreenSpace(settings, OutputMode::ShadowAov,
                                                         (std::string("blend ") + cascadeBlendName(blend)).c_str());
        EXPECT_GE(d.withinPercent, 99.9) << cascadeBlendName(blend);
    }
}
