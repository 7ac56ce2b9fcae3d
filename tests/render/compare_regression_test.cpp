// Regression thresholds: the rasterized shadow AOV of every directional canonical scene (tests/scenes/)
// against the ray-traced reference, per directional filter. Each limit is the value measured on
// lavapipe at 256x144 (in the comment) plus a modest margin; the shadow issues tighten them.
// Reproduce one row: ./build/penumbra compare tests/scenes/SCENE.gltf --width 256 --height 144
//                    --set shadows.directional.filter=PCF5x5 [--set shadows.maxDistance=150]
#include <algorithm>
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

// The 140-145 m casters of near_far_casters and far_field need a shadow distance beyond the default 100 m.
Settings settingsFor(const Limits& limits) {
    Settings settings;
    settings.shadows.directional.filter = limits.filter;
    const std::string scene = limits.scene;
    if (scene == "near_far_casters" || scene == "far_field") settings.shadows.maxDistance = 150.0f;
    return settings;
}

// clang-format off
const Limits kLimits[] = {
    // limits = measured x 1.15 + 0.03 (misclassified %), x 1.5 + 0.01 (interior %), x 1.2 + 0.0005 (MAE),
    // tight enough that a 2 px shift breaks every row (ShadowShiftedTwoPixelsBreaksTheLimits); measured on
    // lavapipe (Mesa llvmpipe), 256x144, default settings but the filter (and settingsFor): since issue 13
    // the receiver-plane bias (shaders/shadow_bias.glsl), the reference's shadow rays starting a few ulps
    // off the surface. The issue-4 limits (normal-bias unit, old reference) were e.g. thin_wall PCF7x7
    // 1.89 % (measured 1.467), near_far_casters PCF7x7 1.64 % (1.266).
    // scene                filter               mis %  int. %   MAE      measured: mis %, interior %, MAE
    {"near_far_casters", ShadowFilter::PCF2x2, 0.341, 0.010, 0.0049},  // measured 0.271 0.000 0.0036
    {"near_far_casters", ShadowFilter::PCF3x3, 0.324, 0.010, 0.0084},  // measured 0.256 0.000 0.0066
    {"near_far_casters", ShadowFilter::PCF5x5, 0.445, 0.010, 0.0138},  // measured 0.361 0.000 0.0111
    {"near_far_casters", ShadowFilter::PCF7x7, 0.462, 0.010, 0.0190},  // measured 0.376 0.000 0.0154
    {"thin_wall",        ShadowFilter::PCF2x2, 0.292, 0.010, 0.0046},  // measured 0.228 0.000 0.0034
    {"thin_wall",        ShadowFilter::PCF3x3, 0.254, 0.010, 0.0068},  // measured 0.195 0.000 0.0053
    {"thin_wall",        ShadowFilter::PCF5x5, 0.221, 0.010, 0.0103},  // measured 0.166 0.000 0.0082
    {"thin_wall",        ShadowFilter::PCF7x7, 0.238, 0.010, 0.0141},  // measured 0.180 0.000 0.0114
    {"poles",            ShadowFilter::PCF2x2, 0.280, 0.010, 0.0040},  // measured 0.218 0.000 0.0029
    {"poles",            ShadowFilter::PCF3x3, 0.309, 0.010, 0.0060},  // measured 0.242 0.000 0.0046
    {"poles",            ShadowFilter::PCF5x5, 0.445, 0.010, 0.0085},  // measured 0.361 0.000 0.0067
    {"poles",            ShadowFilter::PCF7x7, 0.707, 0.010, 0.0105},  // measured 0.588 0.000 0.0083
    {"grazing",          ShadowFilter::PCF2x2, 0.185, 0.010, 0.0023},  // measured 0.135 0.000 0.0015
    {"grazing",          ShadowFilter::PCF3x3, 0.194, 0.010, 0.0034},  // measured 0.142 0.000 0.0024
    {"grazing",          ShadowFilter::PCF5x5, 0.185, 0.010, 0.0052},  // measured 0.135 0.000 0.0039
    {"grazing",          ShadowFilter::PCF7x7, 0.181, 0.010, 0.0070},  // measured 0.131 0.000 0.0054
    {"foliage",          ShadowFilter::PCF2x2, 0.211, 0.010, 0.0033},  // measured 0.158 0.000 0.0023
    {"foliage",          ShadowFilter::PCF3x3, 0.187, 0.010, 0.0048},  // measured 0.136 0.000 0.0036
    {"foliage",          ShadowFilter::PCF5x5, 0.226, 0.010, 0.0069},  // measured 0.170 0.000 0.0054
    {"foliage",          ShadowFilter::PCF7x7, 0.295, 0.010, 0.0091},  // measured 0.230 0.000 0.0072
    {"low_sun",          ShadowFilter::PCF2x2, 0.083, 0.010, 0.0018},  // measured 0.046 0.000 0.0011
    {"low_sun",          ShadowFilter::PCF3x3, 0.093, 0.010, 0.0031},  // measured 0.055 0.000 0.0022
    {"low_sun",          ShadowFilter::PCF5x5, 0.093, 0.010, 0.0050},  // measured 0.055 0.000 0.0037
    {"low_sun",          ShadowFilter::PCF7x7, 0.188, 0.010, 0.0069},  // measured 0.137 0.000 0.0054
    {"far_field",        ShadowFilter::PCF2x2, 0.215, 0.010, 0.0032},  // measured 0.161 0.000 0.0023
    {"far_field",        ShadowFilter::PCF3x3, 0.162, 0.010, 0.0057},  // measured 0.114 0.000 0.0043
    {"far_field",        ShadowFilter::PCF5x5, 0.150, 0.010, 0.0099},  // measured 0.104 0.000 0.0078
    {"far_field",        ShadowFilter::PCF7x7, 0.191, 0.010, 0.0145},  // measured 0.140 0.000 0.0116
    {"thin_slabs",       ShadowFilter::PCF2x2, 0.534, 0.010, 0.0078},  // measured 0.438 0.000 0.0061
    {"thin_slabs",       ShadowFilter::PCF3x3, 0.496, 0.010, 0.0111},  // measured 0.405 0.000 0.0088
    {"thin_slabs",       ShadowFilter::PCF5x5, 0.646, 0.010, 0.0151},  // measured 0.536 0.000 0.0121
    {"thin_slabs",       ShadowFilter::PCF7x7, 0.646, 0.010, 0.0188},  // measured 0.536 0.000 0.0152
    {"grazing_sun",      ShadowFilter::PCF2x2, 0.158, 0.010, 0.0025},  // measured 0.112 0.000 0.0017
    {"grazing_sun",      ShadowFilter::PCF3x3, 0.119, 0.010, 0.0037},  // measured 0.077 0.000 0.0026
    {"grazing_sun",      ShadowFilter::PCF5x5, 0.104, 0.010, 0.0056},  // measured 0.064 0.000 0.0042
    {"grazing_sun",      ShadowFilter::PCF7x7, 0.104, 0.010, 0.0078},  // measured 0.064 0.000 0.0061
    {"fence",            ShadowFilter::PCF2x2, 0.150, 0.010, 0.0024},  // measured 0.104 0.000 0.0016
    {"fence",            ShadowFilter::PCF3x3, 0.140, 0.010, 0.0034},  // measured 0.096 0.000 0.0024
    {"fence",            ShadowFilter::PCF5x5, 0.178, 0.010, 0.0047},  // measured 0.129 0.000 0.0035
    {"fence",            ShadowFilter::PCF7x7, 0.255, 0.010, 0.0061},  // measured 0.196 0.000 0.0047
    {"field_of_objects", ShadowFilter::PCF2x2, 0.182, 0.029, 0.0025},  // measured 0.132 0.013 0.0017
    {"field_of_objects", ShadowFilter::PCF3x3, 0.175, 0.019, 0.0036},  // measured 0.126 0.006 0.0026
    {"field_of_objects", ShadowFilter::PCF5x5, 0.182, 0.010, 0.0052},  // measured 0.132 0.000 0.0039
    {"field_of_objects", ShadowFilter::PCF7x7, 0.248, 0.010, 0.0071},  // measured 0.190 0.000 0.0055
    {"cube",             ShadowFilter::PCF2x2, 0.097, 0.010, 0.0013},  // measured 0.058 0.000 0.0007
    {"cube",             ShadowFilter::PCF3x3, 0.088, 0.010, 0.0017},  // measured 0.051 0.000 0.0010
    {"cube",             ShadowFilter::PCF5x5, 0.084, 0.010, 0.0023},  // measured 0.047 0.000 0.0015
    {"cube",             ShadowFilter::PCF7x7, 0.080, 0.010, 0.0032},  // measured 0.043 0.000 0.0022
    {"cad_engine",       ShadowFilter::PCF2x2, 0.343, 0.010, 0.0058},  // measured 0.272 0.000 0.0044
    {"cad_engine",       ShadowFilter::PCF3x3, 0.314, 0.010, 0.0094},  // measured 0.247 0.000 0.0074
    {"cad_engine",       ShadowFilter::PCF5x5, 0.354, 0.024, 0.0146},  // measured 0.282 0.010 0.0118
    {"cad_engine",       ShadowFilter::PCF7x7, 0.440, 0.072, 0.0203},  // measured 0.391 0.042 0.0165
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
// defect 5: the old PCF7x7 rows let a 2 px shift pass). Along each axis at least one of the two shifts
// must break the limit (one of them can cancel a sub-texel offset the render already has: a caster edge
// parallel to the texel grid snaps to texel centres, up to half a texel, 1.4 px on cad_engine), and so
// must their mean.
TEST_P(DirectionalCompare, ShadowShiftedTwoPixelsBreaksTheLimits) {
    const Limits& limits = GetParam();
    const SceneComparison result = compareCanonicalScene(limits.scene, 0, settingsFor(limits));
    const ReferenceImages& reference = cachedReference(limits.scene, 0, settingsFor(limits));
    double sum = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        double worst = 0.0;
        for (int sign : {-2, 2}) {
            const glm::ivec2 shift = axis == 0 ? glm::ivec2(sign, 0) : glm::ivec2(0, sign);
            const CompareMetrics m = compareShadowImages(shifted(result.ours.image, shift.x, shift.y), reference.shadow,
                                                         reference.validMask);
            std::printf("shifted (%d, %d) %s/%s: misclassified %.3f %%, edge error %.2f px\n", shift.x, shift.y,
                        limits.scene, shadowFilterName(limits.filter), m.misclassifiedPercent, m.edgeErrorPixels);
            worst = std::max(worst, m.misclassifiedPercent);
            sum += m.misclassifiedPercent;
        }
        EXPECT_GT(worst, limits.misclassifiedPercent) << (axis == 0 ? "x" : "y");
    }
    EXPECT_GT(sum / 4.0, limits.misclassifiedPercent);
}

INSTANTIATE_TEST_SUITE_P(CanonicalScenes, DirectionalCompare, ::testing::ValuesIn(kLimits), testName);

// Every directional scene has shadows in view: the reference shows shadowed pixels, so a rasterizer
// that drew no shadows at all would fail the thresholds above.
TEST_F(CompareTest, EveryDirectionalSceneHasShadowsInView) {
    for (const char* scene : {"near_far_casters", "thin_wall", "poles", "grazing", "foliage", "low_sun", "far_field",
                              "thin_slabs", "grazing_sun", "fence", "field_of_objects", "cube", "cad_engine"}) {
        Settings settings;
        const std::string name = scene;
        settings.shadows.maxDistance = name == "near_far_casters" || name == "far_field" ? 150.0f : 100.0f;
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
