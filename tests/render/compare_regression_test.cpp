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
    // measured on lavapipe (Mesa llvmpipe), 256x144, default settings but the filter (and settingsFor),
    // with the normal-bias unit texel diagonal * (1 + filter / 2) (shadow_gpu_packing.cpp). The seed's
    // (filter + 1) unit measured e.g. thin_wall PCF7x7 2.251 0.275 0.0249, near_far_casters PCF7x7
    // 2.048 0.486 0.0213.
    // scene                filter               mis %  int. %   MAE      measured: mis %, interior %, MAE
    // near_far_casters re-measured once the reference's shadow rays stopped starting 6 cm off its 600 m
    // ground (the old limits were 0.47 / 0.98 / 1.40 / 1.64 %).
    {"near_far_casters", ShadowFilter::PCF2x2,  0.65, 0.020, 0.0078},  // measured 0.549 0.004 0.0061
    {"near_far_casters", ShadowFilter::PCF3x3,  1.10, 0.150, 0.0132},  // measured 0.958 0.088 0.0105
    {"near_far_casters", ShadowFilter::PCF5x5,  1.48, 0.360, 0.0186},  // measured 1.296 0.223 0.0148
    {"near_far_casters", ShadowFilter::PCF7x7,  1.68, 0.520, 0.0235},  // measured 1.484 0.335 0.0187
    {"thin_wall",        ShadowFilter::PCF2x2,  0.83, 0.020, 0.0092},  // measured 0.617 0.000 0.0065
    {"thin_wall",        ShadowFilter::PCF3x3,  1.18, 0.020, 0.0134},  // measured 0.897 0.000 0.0099
    {"thin_wall",        ShadowFilter::PCF5x5,  1.57, 0.020, 0.0182},  // measured 1.211 0.000 0.0137
    {"thin_wall",        ShadowFilter::PCF7x7,  1.70, 0.020, 0.0229},  // measured 1.467 0.000 0.0175 (x 1.1 + 0.05: a 2 px shift gives 1.80)
    {"poles",            ShadowFilter::PCF2x2,  0.37, 0.020, 0.0049},  // measured 0.252 0.000 0.0031
    {"poles",            ShadowFilter::PCF3x3,  0.37, 0.020, 0.0069},  // measured 0.252 0.000 0.0047
    {"poles",            ShadowFilter::PCF5x5,  0.54, 0.020, 0.0097},  // measured 0.386 0.000 0.0069
    {"poles",            ShadowFilter::PCF7x7,  0.81, 0.020, 0.0117},  // measured 0.608 0.000 0.0085
    {"grazing",          ShadowFilter::PCF2x2,  0.34, 0.020, 0.0040},  // measured 0.225 0.000 0.0024
    {"grazing",          ShadowFilter::PCF3x3,  0.49, 0.050, 0.0060},  // measured 0.349 0.020 0.0040
    {"grazing",          ShadowFilter::PCF5x5,  0.64, 0.062, 0.0083},  // measured 0.472 0.028 0.0058
    {"grazing",          ShadowFilter::PCF7x7,  0.77, 0.080, 0.0105},  // measured 0.574 0.040 0.0076
    {"foliage",          ShadowFilter::PCF2x2,  0.50, 0.020, 0.0057},  // measured 0.354 0.000 0.0037
    {"foliage",          ShadowFilter::PCF3x3,  0.69, 0.020, 0.0082},  // measured 0.511 0.000 0.0057
    {"foliage",          ShadowFilter::PCF5x5,  0.90, 0.020, 0.0110},  // measured 0.673 0.000 0.0080
    {"foliage",          ShadowFilter::PCF7x7,  1.05, 0.020, 0.0137},  // measured 0.793 0.000 0.0101
    {"low_sun",          ShadowFilter::PCF2x2,  0.29, 0.020, 0.0037},  // measured 0.187 0.000 0.0021
    {"low_sun",          ShadowFilter::PCF3x3,  0.33, 0.020, 0.0050},  // measured 0.224 0.000 0.0032
    {"low_sun",          ShadowFilter::PCF5x5,  0.40, 0.020, 0.0067},  // measured 0.279 0.000 0.0045
    {"low_sun",          ShadowFilter::PCF7x7,  0.50, 0.020, 0.0097},  // measured 0.357 0.000 0.0069
};
// clang-format on

class DirectionalCompare : public CompareTest, public ::testing::WithParamInterface<Limits> {};

std::string testName(const ::testing::TestParamInfo<Limits>& info) {
    return std::string(info.param.scene) + "_" + shadowFilterName(info.param.filter);
}

// Our AOV moved by (dx, dy) pixels, the vacated border lit.
Image shifted(const Image& image, int dx, int dy) {
    Image moved(image.width, image.height, 1, 255);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const int sx = int(x) - dx, sy = int(y) - dy;
            if (sx >= 0 && sy >= 0 && sx < int(image.width) && sy < int(image.height))
                moved.at(x, y) = image.at(uint32_t(sx), uint32_t(sy));
        }
    return moved;
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

// The limits have teeth: the same AOV with its shadows displaced by 2 pixels breaks them (issue 13,
// defect 5: the old PCF7x7 rows let a 2 px shift pass).
TEST_P(DirectionalCompare, ShadowShiftedTwoPixelsBreaksTheLimits) {
    const Limits& limits = GetParam();
    const SceneComparison result = compareCanonicalScene(limits.scene, 0, settingsFor(limits));
    const ReferenceImages& reference = cachedReference(limits.scene, 0, settingsFor(limits));
    for (const glm::ivec2 shift : {glm::ivec2(2, 0), glm::ivec2(0, 2)}) {
        const CompareMetrics m = compareShadowImages(shifted(result.ours.image, shift.x, shift.y), reference.shadow,
                                                     reference.validMask);
        std::printf("shifted (%d, %d) %s/%s: misclassified %.3f %%, edge error %.2f px\n", shift.x, shift.y,
                    limits.scene, shadowFilterName(limits.filter), m.misclassifiedPercent, m.edgeErrorPixels);
        EXPECT_GT(m.misclassifiedPercent, limits.misclassifiedPercent) << "shift " << shift.x << ", " << shift.y;
    }
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

// Spot lights (issue 5), light 0 soft (PCF5x5), light 1 hard; limits = measured with the margins of kLimits.
// Measured on lavapipe, 256x144, default settings (shadowNormalBias 1, spot.depthBias 0):
//   soft: misclassified 0.344 %, interior 0.000 %, MAE 0.0064; hard: 0.156 %, 0.000 %, 0.0025.
// Reproduce: ./build/penumbra compare tests/scenes/spot_lights.gltf --light N --width 256 --height 144
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
        const double misclassifiedLimit[2] = {0.48, 0.25};
        const double maeLimit[2] = {0.0090, 0.0041};
        EXPECT_LE(result.metrics.misclassifiedPercent, misclassifiedLimit[light]);
        EXPECT_LE(result.metrics.interiorMisclassifiedPercent, 0.020);
        EXPECT_LE(result.metrics.meanAbsoluteError, maeLimit[light]);
    }
}
