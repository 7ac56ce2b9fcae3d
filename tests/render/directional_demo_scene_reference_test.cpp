// The sun's shadow in the built-in demo scene (boxes, spheres, a thin wall, far objects, an alpha-clipped
// quad, a dithered sphere, an unlit box) against the ray-traced reference, for each filter and cascade blend
// mode with the default settings (atlas 1024, 4 cascades, 100 m).
#include <cstdio>

#include "directional_shadow_scenes.h"

#include "scene/demo_scene.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 192, kHeight = 108;

// Thresholds from measurement on lavapipe (printed by each test), with headroom. Measured misclassified
// 0.51 / 0.62 / 0.66 / 0.72 % for PCF2x2 / 3x3 / 5x5 / 7x7 (soft and dither with PCF5x5: 0.66 %) and 0 %
// in the interior: the errors sit on shadow edges, which the wider filters and the normal bias move.
// (With Catlike Coding's (filter + 1) normal-bias unit: 0.51 / 0.63 / 0.76 / 0.88 %.)
constexpr double kMaxMisclassifiedPercent = 1.0;
constexpr double kMaxInteriorMisclassifiedPercent = 0.1;

class DemoSceneReferenceTest : public DirectionalShadowTest {
protected:
    CompareMetrics measure(const Settings& settings, const std::string& what) {
        static const Scene scene = makeDemoScene();
        const Image aov =
            renderScene(scene, RenderRequest{kWidth, kHeight, OutputMode::ShadowAov, 0, false}, settings).image;
        const CompareMetrics m = compareWithReference(scene, aov, settings);
        std::printf("[demo scene] %-14s misclassified %.3f %%  interior %.3f %%  (valid %llu)\n", what.c_str(),
                    m.misclassifiedPercent, m.interiorMisclassifiedPercent,
                    static_cast<unsigned long long>(m.validPixels));
        EXPECT_GT(m.validPixels, uint64_t(kWidth * kHeight / 3)) << what;
        EXPECT_LT(m.misclassifiedPercent, kMaxMisclassifiedPercent) << what;
        EXPECT_LT(m.interiorMisclassifiedPercent, kMaxInteriorMisclassifiedPercent) << what;
        return m;
    }
};

}  // namespace

TEST_F(DemoSceneReferenceTest, SunShadowMatchesTheReferenceWithEachFilter) {
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        Settings settings;
        settings.shadows.directional.filter = filter;
        measure(settings, shadowFilterName(filter));
    }
}

TEST_F(DemoSceneReferenceTest, SunShadowMatchesTheReferenceWithEachCascadeBlend) {
    for (CascadeBlend blend : {CascadeBlend::Soft, CascadeBlend::Dither}) {
        Settings settings;
        settings.shadows.directional.filter = ShadowFilter::PCF5x5;
        settings.shadows.directional.cascadeBlend = blend;
        measure(settings, std::string("PCF5x5 ") + cascadeBlendName(blend));
    }
}
