// The point light canonical scene: its shadows surround the light. Its error limits are a row of
// OtherLightCompare (compare_regression_test.cpp).
#include <gtest/gtest.h>

#include "compare_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

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
