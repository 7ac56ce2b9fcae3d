// Regression thresholds: the rasterized shadow AOV of every directional canonical scene (tests/scenes/)
// against the ray-traced reference, per directional filter. Each limit is the value measured on
// lavapipe at 256x144 (in the comment) plus a modest margin; the shadow issues tighten them.
// Reproduce one row: ./build/penumbra compare tests/scenes/SCENE.gltf --width 256 --height 144
//                    --set shadows.directional.filter=PCF5x5 [--set shadows.maxDistance=150]
#include <cstdio>
#include <ostream>

#include <gtest/gtest.h>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Limits {
    const char* scene;
    ShadowFilter filter;
    double misclassifiedPercent;          // of the valid pixels
    double interiorMisclassifiedPercent;  // acne, leaks, peter-panning: away from shadow edges
    double meanAbsoluteError;
};

std::ostream& operator<<(std::ostream& out, const Limits& limits) {
    return out << limits.scene << "/" << shadowFilterName(limits.filter);
}

// The 140 m casters of near_far_casters need a shadow distance beyond the default 100 m.
Settings settingsFor(const Limits& limits) {
    Settings settings;
    settings.shadows.directional.filter = limits.filter;
    if (std::string(limits.scene) == "near_far_casters") settings.shadows.maxDistance = 150.0f;
    return settings;
}

// clang-format off
const Limits kLimits[] = {
    // limits = measured x 1.25 + 0.05 (misclassified %), x 1.5 + 0.02 (interior %), x 1.25 + 0.001 (MAE);
    // measured on lavapipe (Mesa llvmpipe), 256x144, default settings but the filter (and settingsFor).
    // scene                filter               mis %  int. %   MAE      measured: mis %, interior %, MAE
    {"near_far_casters", ShadowFilter::PCF2x2,  0.47, 0.020, 0.0068},  // measured 0.331 0.000 0.0046
    {"near_far_casters", ShadowFilter::PCF3x3,  1.26, 0.133, 0.0145},  // measured 0.966 0.075 0.0108
    {"near_far_casters", ShadowFilter::PCF5x5,  1.84, 0.458, 0.0220},  // measured 1.432 0.292 0.0168
    {"near_far_casters", ShadowFilter::PCF7x7,  2.61, 0.749, 0.0277},  // measured 2.048 0.486 0.0213
    {"thin_wall",        ShadowFilter::PCF2x2,  0.83, 0.020, 0.0092},  // measured 0.617 0.000 0.0065
    {"thin_wall",        ShadowFilter::PCF3x3,  1.53, 0.020, 0.0168},  // measured 1.182 0.000 0.0126
    {"thin_wall",        ShadowFilter::PCF5x5,  2.19, 0.044, 0.0245},  // measured 1.705 0.016 0.0188
    {"thin_wall",        ShadowFilter::PCF7x7,  2.87, 0.433, 0.0322},  // measured 2.251 0.275 0.0249
    {"poles",            ShadowFilter::PCF2x2,  0.37, 0.020, 0.0049},  // measured 0.252 0.000 0.0031
    {"poles",            ShadowFilter::PCF3x3,  0.38, 0.020, 0.0072},  // measured 0.262 0.000 0.0049
    {"poles",            ShadowFilter::PCF5x5,  0.56, 0.020, 0.0103},  // measured 0.405 0.000 0.0074
    {"poles",            ShadowFilter::PCF7x7,  0.84, 0.020, 0.0119},  // measured 0.628 0.000 0.0087
    {"grazing",          ShadowFilter::PCF2x2,  0.34, 0.020, 0.0040},  // measured 0.225 0.000 0.0024
    {"grazing",          ShadowFilter::PCF3x3,  0.63, 0.062, 0.0074},  // measured 0.461 0.028 0.0051
    {"grazing",          ShadowFilter::PCF5x5,  0.92, 0.116, 0.0109},  // measured 0.690 0.064 0.0079
    {"grazing",          ShadowFilter::PCF7x7,  1.19, 0.157, 0.0144},  // measured 0.911 0.091 0.0107
    {"foliage",          ShadowFilter::PCF2x2,  0.50, 0.020, 0.0057},  // measured 0.354 0.000 0.0037
    {"foliage",          ShadowFilter::PCF3x3,  0.91, 0.020, 0.0100},  // measured 0.686 0.000 0.0072
    {"foliage",          ShadowFilter::PCF5x5,  1.31, 0.020, 0.0144},  // measured 1.001 0.000 0.0107
    {"foliage",          ShadowFilter::PCF7x7,  1.64, 0.028, 0.0183},  // measured 1.266 0.005 0.0138
    {"low_sun",          ShadowFilter::PCF2x2,  0.29, 0.020, 0.0037},  // measured 0.187 0.000 0.0021
    {"low_sun",          ShadowFilter::PCF3x3,  0.40, 0.020, 0.0057},  // measured 0.279 0.000 0.0037
    {"low_sun",          ShadowFilter::PCF5x5,  0.55, 0.028, 0.0082},  // measured 0.393 0.005 0.0057
    {"low_sun",          ShadowFilter::PCF7x7,  0.79, 0.035, 0.0108},  // measured 0.590 0.010 0.0078
};
// clang-format on

class DirectionalCompare : public CompareTest, public ::testing::WithParamInterface<Limits> {};

std::string testName(const ::testing::TestParamInfo<Limits>& info) {
    return std::string(info.param.scene) + "_" + shadowFilterName(info.param.filter);
}

}  // namespace

TEST_P(DirectionalCompare, ShadowStaysWithinTheMeasuredErrorOfTheReference) {
    const Limits& limits = GetParam();
    const SceneComparison result = compareCanonicalScene(limits.scene, 0, settingsFor(limits));
    const CompareMetrics& m = result.metrics;
    // The measured row, for re-deriving the limits (tests/scenes/compare_table.sh prints the same).
    std::printf("measured %s/%s: misclassified %.3f %%, interior %.3f %%, MAE %.4f\n", limits.scene,
                shadowFilterName(limits.filter), m.misclassifiedPercent, m.interiorMisclassifiedPercent,
                m.meanAbsoluteError);
    ASSERT_GT(m.validPixels, kCompareWidth * kCompareHeight / 10) << "the scene should fill the view";
    ASSERT_GT(m.interiorPixels, 0u);
    EXPECT_LE(m.misclassifiedPercent, limits.misclassifiedPercent);
    EXPECT_LE(m.interiorMisclassifiedPercent, limits.interiorMisclassifiedPercent);
    EXPECT_LE(m.meanAbsoluteError, limits.meanAbsoluteError);
}

INSTANTIATE_TEST_SUITE_P(CanonicalScenes, DirectionalCompare, ::testing::ValuesIn(kLimits), testName);

// Every directional scene has shadows in view: the reference shows shadowed pixels, so a rasterizer
// that drew no shadows at all would fail the thresholds above.
TEST_F(CompareTest, EveryDirectionalSceneHasShadowsInView) {
    for (const char* scene : {"near_far_casters", "thin_wall", "poles", "grazing", "foliage", "low_sun"}) {
        Settings settings;
        settings.shadows.maxDistance = std::string(scene) == "near_far_casters" ? 150.0f : 100.0f;
        const ReferenceImages& reference = cachedReference(scene, 0, settings);
        uint64_t shadowed = 0;
        for (uint32_t i = 0; i < reference.shadow.pixels.size(); ++i)
            if (reference.validMask.pixels[i] != 0 && reference.shadow.pixels[i] < 128) ++shadowed;
        // Over 0.5 % of the compared pixels: the poles' shadows are one or two pixels wide.
        EXPECT_GT(shadowed, reference.validPixels / 200) << scene;
    }
}

// A real reference image compared with itself: nothing misclassified, no error.
TEST_F(CompareTest, ReferenceComparedWithItselfHasNoError) {
    const ReferenceImages& reference = cachedReference("foliage", 0, Settings{});
    const CompareMetrics m = compareShadowImages(reference.shadow, reference.shadow, reference.validMask);
    EXPECT_EQ(m.validPixels, reference.validPixels);
    EXPECT_EQ(m.falseShadow + m.falseLit, 0u);
    EXPECT_EQ(m.meanAbsoluteError, 0.0);
}

// Spot lights (issue 5). The limits are provisional, NOT measured: the rasterizer has no spot shadows
// yet, so the test skips until it has; the issue-5 work measures and tightens them.
TEST_F(CompareTest, SpotLightShadowsStayWithinTheErrorOfTheReference) {
    const char* names[2] = {"soft", "hard"};
    for (uint32_t light : {0u, 1u}) {
        SCOPED_TRACE(names[light]);
        const SceneComparison result = compareCanonicalScene("spot_lights", light, Settings{});
        if (otherLightShadowsMissing(result.ours))
            GTEST_SKIP() << "the rasterizer casts no spot-light shadows yet (issue 5): its AOV is all lit and its "
                            "stats report no spot shadows";
        std::cout << "spot_lights light " << light << " " << toJson(result.metrics) << "\n";
        EXPECT_GT(result.metrics.validPixels, kCompareWidth * kCompareHeight / 10);
        EXPECT_LE(result.metrics.misclassifiedPercent, 10.0);
        EXPECT_LE(result.metrics.interiorMisclassifiedPercent, 3.0);
    }
}
