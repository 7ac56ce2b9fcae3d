// Comparison of a rendered shadow AOV with the reference (reference/compare.h).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "penumbra/shadow_compare.h"

namespace penumbra {
namespace {

// 16x16, shadowed (0) for x < 8 and lit (255) for x >= 8: the boundary runs between columns 7 and 8.
Image halfShadowed() {
    Image image(16, 16, 1, 255);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 8; ++x) image.at(x, y) = 0;
    return image;
}

const Image kAllValid(16, 16, 1, 255);

TEST(CompareShadowImages, ImageComparedWithItselfHasNoErrors) {
    const Image reference = halfShadowed();
    const CompareMetrics m = compareShadowImages(reference, reference, kAllValid);
    EXPECT_EQ(m.validPixels, 256u);
    EXPECT_EQ(m.falseShadow, 0u);
    EXPECT_EQ(m.falseLit, 0u);
    EXPECT_EQ(m.interiorFalseShadow + m.interiorFalseLit, 0u);
    EXPECT_EQ(m.misclassifiedPercent, 0.0);
    EXPECT_EQ(m.interiorMisclassifiedPercent, 0.0);
    EXPECT_EQ(m.meanAbsoluteError, 0.0);
}

TEST(CompareShadowImages, CountsFalseShadowAndFalseLitPixels) {
    const Image reference = halfShadowed();
    Image ours = reference;
    ours.at(13, 8) = 127;  // lit in the reference: false shadow
    ours.at(2, 8) = 128;   // shadowed in the reference: false lit
    ours.at(7, 3) = 200;   // false lit, next to the boundary
    const CompareMetrics m = compareShadowImages(ours, reference, kAllValid);
    EXPECT_EQ(m.falseShadow, 1u);
    EXPECT_EQ(m.falseLit, 2u);
    EXPECT_DOUBLE_EQ(m.falseShadowPercent, 100.0 / 256.0);
    EXPECT_DOUBLE_EQ(m.falseLitPercent, 200.0 / 256.0);
    EXPECT_DOUBLE_EQ(m.misclassifiedPercent, 300.0 / 256.0);
    EXPECT_NEAR(m.meanAbsoluteError, (128.0 + 128.0 + 200.0) / 255.0 / 256.0, 1e-12);
}

TEST(CompareShadowImages, InteriorExcludesPixelsWithinTwoOfTheReferenceBoundary) {
    const Image reference = halfShadowed();
    Image ours = reference;
    ours.at(13, 8) = 0;    // interior false shadow
    ours.at(2, 8) = 255;   // interior false lit
    ours.at(7, 3) = 255;   // 1 pixel from the boundary
    ours.at(9, 12) = 0;    // 2 pixels from the boundary
    const CompareMetrics m = compareShadowImages(ours, reference, kAllValid);
    EXPECT_EQ(m.interiorPixels, 256u - 4u * 16u);  // columns 6..9 are near the boundary
    EXPECT_EQ(m.interiorFalseShadow, 1u);
    EXPECT_EQ(m.interiorFalseLit, 1u);
    EXPECT_DOUBLE_EQ(m.interiorMisclassifiedPercent, 200.0 / 192.0);
    EXPECT_EQ(m.falseShadow + m.falseLit, 4u);
}

TEST(CompareShadowImages, PixelsOutsideTheValidMaskAreIgnored) {
    const Image reference = halfShadowed();
    Image ours = reference;
    ours.at(13, 8) = 0;
    Image mask = kAllValid;
    mask.at(13, 8) = 0;
    const CompareMetrics m = compareShadowImages(ours, reference, mask);
    EXPECT_EQ(m.validPixels, 255u);
    EXPECT_EQ(m.falseShadow, 0u);
    EXPECT_EQ(m.meanAbsoluteError, 0.0);
}

TEST(CompareShadowImages, ThresholdSeparatesWeakShadowsFromLight) {
    // Strength 0.4: shadowed pixels are 255 × 0.6 = 153, above the default threshold.
    Image reference(4, 1, 1, 255);
    reference.at(0, 0) = 153;
    const Image ours(4, 1, 1, 255);
    const Image mask(4, 1, 1, 255);
    EXPECT_EQ(compareShadowImages(ours, reference, mask).falseLit, 0u);
    EXPECT_EQ(compareShadowImages(ours, reference, mask, 0.8f).falseLit, 1u);
}

TEST(CompareShadowImages, EmptyValidMaskGivesZeroPercentages) {
    const Image reference = halfShadowed();
    const CompareMetrics m = compareShadowImages(Image(16, 16, 1, 255), reference, Image(16, 16, 1, 0));
    EXPECT_EQ(m.validPixels, 0u);
    EXPECT_EQ(m.misclassifiedPercent, 0.0);
    EXPECT_EQ(m.meanAbsoluteError, 0.0);
}

TEST(CompareShadowImages, SizeMismatchIsAnError) {
    try {
        compareShadowImages(Image(8, 16, 1), halfShadowed(), kAllValid);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "compare: the rendered image is 8x16 but the reference image is 16x16");
    }
    EXPECT_THROW(compareShadowImages(halfShadowed(), halfShadowed(), Image(16, 15, 1)), Error);
}

TEST(CompareShadowImages, ThresholdOutsideTheUnitIntervalIsAnError) {
    EXPECT_THROW(compareShadowImages(halfShadowed(), halfShadowed(), kAllValid, 0.0f), Error);
    EXPECT_THROW(compareShadowImages(halfShadowed(), halfShadowed(), kAllValid, 1.5f), Error);
}

// halfShadowed() with its edge moved by `shift` columns (positive: the shadow grows to the right).
Image edgeAt(int shift) {
    Image image(16, 16, 1, 255);
    for (uint32_t y = 0; y < 16; ++y)
        for (int x = 0; x < 8 + shift; ++x) image.at(uint32_t(x), y) = 0;
    return image;
}

TEST(CompareShadowImages, EdgePixelsAreTheShadowedSideOfTheReferenceEdge) {
    const CompareMetrics m = compareShadowImages(halfShadowed(), halfShadowed(), kAllValid);
    EXPECT_EQ(m.edgePixels, 16u);  // column 7, one per row
    EXPECT_EQ(m.edgeErrorPixels, 0.0);
    EXPECT_EQ(m.edgeBalance, 0.0);
}

TEST(CompareShadowImages, EdgeErrorIsTheDisplacementOfAShiftedEdgeInPixels) {
    EXPECT_DOUBLE_EQ(compareShadowImages(edgeAt(2), halfShadowed(), kAllValid).edgeErrorPixels, 2.0);
    EXPECT_DOUBLE_EQ(compareShadowImages(edgeAt(-3), halfShadowed(), kAllValid).edgeErrorPixels, 3.0);
}

TEST(CompareShadowImages, EdgeBalanceIsPositiveForGrownShadowsAndNegativeForShrunkOnes) {
    EXPECT_DOUBLE_EQ(compareShadowImages(edgeAt(1), halfShadowed(), kAllValid).edgeBalance, 1.0);
    EXPECT_DOUBLE_EQ(compareShadowImages(edgeAt(-1), halfShadowed(), kAllValid).edgeBalance, -1.0);
    Image mixed = halfShadowed();
    for (uint32_t y = 0; y < 4; ++y) mixed.at(8, y) = 0;    // 4 false shadow
    for (uint32_t y = 0; y < 12; ++y) mixed.at(7, y) = 255; // 12 false lit
    EXPECT_DOUBLE_EQ(compareShadowImages(mixed, halfShadowed(), kAllValid).edgeBalance, (4.0 - 12.0) / 16.0);
}

TEST(CompareShimmer, CountsPixelsThatFlipInOursButNotInTheReference) {
    const Image reference = halfShadowed();
    Image ours1 = reference;
    ours1.at(12, 3) = 0;  // ours flips, the truth does not: shimmer
    Image reference1 = reference;
    reference1.at(8, 5) = 0;  // the truth moved here, and ours with it: not shimmer
    ours1.at(8, 5) = 0;
    const ShimmerMetrics s = compareShimmer(reference, ours1, reference, reference1, kAllValid, kAllValid);
    EXPECT_EQ(s.pixels, 256u);
    EXPECT_EQ(s.flickering, 1u);
    EXPECT_EQ(s.referenceFlips, 1u);
    EXPECT_DOUBLE_EQ(s.shimmerPercent, 100.0 / 256.0);
}

TEST(CompareShimmer, InteriorShimmerCountsFlipsAwayFromTheTruthsEdges) {
    Image ours1 = halfShadowed();
    ours1.at(13, 3) = 0;  // 5 columns from the edge: interior
    ours1.at(8, 5) = 0;   // next to the edge: not interior
    const ShimmerMetrics s = compareShimmer(halfShadowed(), ours1, halfShadowed(), halfShadowed(), kAllValid, kAllValid);
    EXPECT_EQ(s.interiorPixels, 256u - 4u * 16u);
    EXPECT_EQ(s.interiorFlickering, 1u);
    EXPECT_EQ(s.flickering, 2u);
}

// A region that changes class in the truth as a whole (a near object shifts by several pixels with the
// camera) holds pixels away from both frames' edges that flip in the truth: ours flipping with it is not
// shimmer there either.
TEST(CompareShimmer, InteriorShimmerLeavesOutPixelsWhoseTruthFlipsToo) {
    Image shifted(16, 16, 1, 255);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 14; ++x) shifted.at(x, y) = 0;  // the edge moved 6 columns
    const ShimmerMetrics s = compareShimmer(halfShadowed(), shifted, halfShadowed(), shifted, kAllValid, kAllValid);
    EXPECT_GT(s.referenceFlips, 0u);
    EXPECT_GT(s.interiorPixels, 0u);
    EXPECT_EQ(s.flickering, 0u);
    EXPECT_EQ(s.interiorFlickering, 0u);
}

TEST(CompareShimmer, OnlyPixelsValidInBothFramesCount) {
    Image ours1 = halfShadowed();
    ours1.at(12, 3) = 0;
    Image mask1 = kAllValid;
    mask1.at(12, 3) = 0;
    const ShimmerMetrics s = compareShimmer(halfShadowed(), ours1, halfShadowed(), halfShadowed(), kAllValid, mask1);
    EXPECT_EQ(s.pixels, 255u);
    EXPECT_EQ(s.flickering, 0u);
}

TEST(MakeDiffImage, MarksFalseShadowRedAndFalseLitCyanOverTheDimmedBase) {
    const Image reference = halfShadowed();
    Image ours = reference;
    ours.at(13, 8) = 0;
    ours.at(2, 8) = 255;
    Image mask = kAllValid;
    mask.at(0, 0) = 0;
    const Image base(16, 16, 1, 200);
    const Image diff = makeDiffImage(base, ours, reference, mask);
    ASSERT_EQ(diff.channels, 3u);
    EXPECT_EQ(diff.at(13, 8, 0), 255);
    EXPECT_EQ(diff.at(13, 8, 1), 0);
    EXPECT_EQ(diff.at(13, 8, 2), 0);
    EXPECT_EQ(diff.at(2, 8, 0), 0);
    EXPECT_EQ(diff.at(2, 8, 1), 255);
    EXPECT_EQ(diff.at(2, 8, 2), 255);
    for (uint32_t c = 0; c < 3; ++c) {
        EXPECT_EQ(diff.at(5, 5, c), 100);  // valid and agreeing: half the base
        EXPECT_EQ(diff.at(0, 0, c), 40);   // excluded: a fifth of the base
    }
}

TEST(MakeDiffImage, KeepsTheColoursOfAnRgbBase) {
    const Image reference = halfShadowed();
    Image base(16, 16, 3, 0);
    base.at(4, 4, 0) = 200;
    base.at(4, 4, 2) = 100;
    const Image diff = makeDiffImage(base, reference, reference, kAllValid);
    EXPECT_EQ(diff.at(4, 4, 0), 100);
    EXPECT_EQ(diff.at(4, 4, 1), 0);
    EXPECT_EQ(diff.at(4, 4, 2), 50);
}

TEST(CompareMetricsReport, JsonHoldsEveryCount) {
    CompareMetrics m;
    m.validPixels = 10;
    m.falseShadow = 2;
    m.interiorFalseLit = 1;
    m.misclassifiedPercent = 20.0;
    const nlohmann::json json = nlohmann::json::parse(toJson(m));
    EXPECT_EQ(json.at("validPixels"), 10);
    EXPECT_EQ(json.at("falseShadow"), 2);
    EXPECT_EQ(json.at("interiorFalseLit"), 1);
    EXPECT_DOUBLE_EQ(json.at("misclassifiedPercent").get<double>(), 20.0);
    EXPECT_TRUE(json.contains("meanAbsoluteError"));
    EXPECT_TRUE(json.contains("interiorMisclassifiedPercent"));
    EXPECT_TRUE(json.contains("edgeErrorPixels"));
    EXPECT_TRUE(json.contains("edgeBalance"));
    EXPECT_FALSE(json.contains("shimmerPercent"));
    ShimmerMetrics shimmer;
    shimmer.shimmerPercent = 0.25;
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(toJson(m, shimmer)).at("shimmerPercent").get<double>(), 0.25);
}

TEST(CompareMetricsReport, TextNamesTheMisclassifiedShare) {
    CompareMetrics m;
    m.validPixels = 400;
    m.falseLit = 3;
    m.misclassifiedPercent = 0.75;
    const std::string text = toText(m);
    EXPECT_NE(text.find("misclassified"), std::string::npos);
    EXPECT_NE(text.find("0.750 %"), std::string::npos);
    EXPECT_NE(text.find("400"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
