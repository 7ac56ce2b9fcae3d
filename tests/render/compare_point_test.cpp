// The point light canonical scene against the ray-traced reference. Point-light shadows arrive with
// issue 5; until the renderer casts them the test skips (see otherLightShadowsMissing). The limits
// are provisional, NOT measured: the issue-5 work measures and tightens them.
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
    EXPECT_LE(result.metrics.misclassifiedPercent, 10.0);
    EXPECT_LE(result.metrics.interiorMisclassifiedPercent, 3.0);
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
