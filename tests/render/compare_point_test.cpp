// The point light canonical scene against the ray-traced reference. Point-light shadows arrive with
// issue 5; until the renderer casts them the test skips (see otherLightShadowsMissing). Limits = measured
// x 1.25 + 0.05 (misclassified %), x 1.5 + 0.02 (interior %), x 1.25 + 0.001 (MAE), as in
// compare_regression_test.cpp. Measured on lavapipe, 256x144, default settings: misclassified 0.425 %,
// interior 0.000 %, MAE 0.0067.
// Reproduce: ./build/penumbra compare tests/scenes/point_light.gltf --width 256 --height 144
#include <gtest/gtest.h>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

TEST_F(CompareTest, PointLightShadowsStayWithinTheErrorOfTheReference) {
    const SceneComparison result = compareCanonicalScene("point_light", 0, Settings{});
    if (otherLightShadowsMissing(result.ours))
        GTEST_SKIP() << "the rasterizer casts no point-light shadows yet (issue 5): its AOV is all lit and its "
                        "stats report no point shadows";
    std::cout << "point_light " << toJson(result.metrics) << "\n";
    EXPECT_GT(result.metrics.validPixels, kCompareWidth * kCompareHeight / 10);
    EXPECT_LE(result.metrics.misclassifiedPercent, 0.58);
    EXPECT_LE(result.metrics.interiorMisclassifiedPercent, 0.020);
    EXPECT_LE(result.metrics.meanAbsoluteError, 0.0094);
}

TEST_F(CompareTest, PointLightSceneHasShadowsAllAroundTheLight) {
    // The reference (no rasterizer needed) shows shadows on both sides of the light: the scene really
    // exercises more than one cube face.
    const ReferenceImages& reference = cachedReference("point_light", 0, Settings{});
    uint64_t left = 0, right = 0;
    for (uint32_t y = 0; y < reference.shadow.height; ++y)
        for (uint32_t x = 0; x < reference.shadow.width; ++x)
            if (reference.validMask.at(x, y) != 0 && reference.shadow.at(x, y) < 128)
                ++(x < reference.shadow.width / 2 ? left : right);
    EXPECT_GT(left, 100u);
    EXPECT_GT(right, 100u);
}
