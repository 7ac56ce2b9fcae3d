#include <gtest/gtest.h>

#include "core/error.h"
#include "penumbra/image_diff.h"

using namespace penumbra;

TEST(ImageDiff, IdenticalImagesDifferByNothing) {
    Image a(4, 3, 3, 77);
    const ImageDifference d = diffImages(a, a);
    EXPECT_EQ(d.maxAbsDifference, 0u);
    EXPECT_EQ(d.meanAbsDifference, 0.0);
    EXPECT_EQ(d.pixelsOver1, 0u);
}

TEST(ImageDiff, CountsPixelsByTheirLargestChannelDifference) {
    Image a(2, 1, 3, 100), b(2, 1, 3, 100);
    b.at(0, 0, 2) = 102;  // one pixel off by 2 in blue
    b.at(1, 0, 0) = 90;   // the other off by 10 in red
    const ImageDifference d = diffImages(a, b);
    EXPECT_EQ(d.maxAbsDifference, 10u);
    EXPECT_EQ(d.pixelsOver1, 2u);
    EXPECT_EQ(d.pixelsOver8, 1u);
    EXPECT_DOUBLE_EQ(d.meanAbsDifference, 12.0 / 6.0);
}

TEST(ImageDiff, RefusesImagesOfDifferentSizes) {
    EXPECT_THROW(diffImages(Image(2, 2, 1), Image(2, 3, 1)), Error);
    EXPECT_THROW(diffImages(Image(2, 2, 1), Image(2, 2, 3)), Error);
}
