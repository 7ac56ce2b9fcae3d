// The virtual shadow map pool's 16-bit depth codes (shadows/virtual_page_depth.h, shaders/shared/
// virtual_page_structs.h "The pool's texels"): what the copy pass stores and the lookups decode.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "shadows/virtual_page_depth.h"

namespace penumbra {
namespace {

using gpu_data::kVirtualPageDepthCodeFar;
using gpu_data::kVirtualPageDepthCodeMax;

float decode(uint32_t code, const VirtualPageDepthRange& range) {
    return gpu_data::virtualPageDecodeDepth(code, range.depthMin, range.depthStep);
}

TEST(VirtualPageDepth, ADecodedDepthIsNeverNearerThanDrawnAndAtMostOneStepFarther) {
    std::mt19937 random(20261207u);
    for (const auto& [low, high] : {std::pair{0.0f, 1.0f}, std::pair{0.41f, 0.4100004f}, std::pair{0.2f, 0.9f}}) {
        std::uniform_real_distribution<float> depth(low, high);
        std::vector<float> page(128 * 128);
        for (float& d : page) d = depth(random);
        page[7] = 1.0f;  // nothing cast there
        const VirtualPageDepthRange range = virtualPageDepthRange(page);
        EXPECT_LE(range.depthMin, high);
        EXPECT_GT(range.depthStep, 0.0f);
        float worst = 0.0f;
        for (float d : page) {
            if (d >= 1.0f) continue;
            const float decoded = decode(virtualPageDepthCode(d, range), range);
            ASSERT_GE(decoded, d) << "rounded up: quantization never shadows what the float depths light";
            worst = std::max(worst, decoded - d);
        }
        EXPECT_LE(worst, range.depthStep * 1.001f + 1e-7f) << "within one step of the page's own range";
        EXPECT_LE(range.depthStep, (high - low) / float(kVirtualPageDepthCodeMax) * 1.01f + 1e-9f);
    }
}

TEST(VirtualPageDepth, FarTexelsDecodeToExactlyOneAndAPageOfOneDepthExactly) {
    const std::vector<float> empty(64, 1.0f);
    const VirtualPageDepthRange none = virtualPageDepthRange(empty);
    EXPECT_EQ(virtualPageDepthCode(1.0f, none), kVirtualPageDepthCodeFar);
    EXPECT_EQ(decode(kVirtualPageDepthCodeFar, none), 1.0f);
    EXPECT_EQ(decode(kVirtualPageDepthCodeFar, {0.25f, 1e-5f}), 1.0f) << "far whatever the range";
    std::vector<float> flat(64, 0.3137f);
    flat[3] = 1.0f;
    const VirtualPageDepthRange one = virtualPageDepthRange(flat);
    EXPECT_EQ(one.depthStep, 0.0f);
    EXPECT_EQ(decode(virtualPageDepthCode(0.3137f, one), one), 0.3137f);
    EXPECT_EQ(virtualPageDepthCode(-0.5f, virtualPageDepthRange(std::vector<float>{-0.5f, 0.5f})), 0u)
        << "a depth nearer than the map's near plane counts as 0, as drawn";
}

TEST(VirtualPageDepth, EveryCodeSurvivesItsTexelValue) {
    // The copy pass stores virtualPageTexelOfCode(code); an R32_SFLOAT pool keeps that value, and the
    // lookup reads the code back with virtualPageCodeOfTexel (an R16_UNORM pool's value is code / 65535).
    for (uint32_t code = 0; code <= kVirtualPageDepthCodeFar; ++code) {
        ASSERT_EQ(gpu_data::virtualPageCodeOfTexel(gpu_data::virtualPageTexelOfCode(code)), code);
        ASSERT_EQ(gpu_data::virtualPageCodeOfTexel(float(double(code) / 65535.0)), code);
        // What an R16_UNORM store keeps of the value, rounding to nearest or truncating: the code.
        const double stored = double(gpu_data::virtualPageTexelOfCode(code)) * 65535.0;
        ASSERT_EQ(uint32_t(std::lround(stored)), code);
        ASSERT_EQ(uint32_t(std::min(stored, 65535.0)), code);
    }
    EXPECT_EQ(gpu_data::virtualPageTexelOfCode(kVirtualPageDepthCodeFar), 1.0f) << "far is the texel value 1";
}

TEST(VirtualPageDepth, PoolBytesOfEitherFormatHoldTheCodes) {
    const std::vector<uint16_t> codes = {0, 1, 12345, uint16_t(kVirtualPageDepthCodeMax), uint16_t(kVirtualPageDepthCodeFar)};
    for (uint32_t texelBytes : {2u, 4u}) {
        const std::vector<uint8_t> bytes = virtualPoolTexelBytes(codes, texelBytes);
        ASSERT_EQ(bytes.size(), codes.size() * texelBytes);
        EXPECT_EQ(virtualPoolCodesOfBytes(bytes, texelBytes), codes) << texelBytes << " bytes a texel";
    }
    float far;  // an R32_SFLOAT pool's far texel is the value 1
    std::memcpy(&far, virtualPoolTexelBytes(std::vector<uint16_t>{uint16_t(kVirtualPageDepthCodeFar)}, 4).data(), 4);
    EXPECT_EQ(far, 1.0f);
}

TEST(VirtualPageDepth, EachPageOfAPoolHasItsOwnRange) {
    // Two pages of 4 texels a side: the left one's depths within 0.1 of 0.2, the right one's 0.6 and far.
    const uint32_t side = 8, pageSize = 4;
    std::vector<float> texels(side * pageSize);
    for (uint32_t y = 0; y < pageSize; ++y)
        for (uint32_t x = 0; x < side; ++x)
            texels[y * side + x] = x < pageSize ? 0.2f + 0.1f * float(x + y) / 6.0f : (x % 2 ? 1.0f : 0.6f);
    const VirtualPoolCodes pool = encodeVirtualPool(texels, side, pageSize);
    ASSERT_EQ(pool.codes.size(), size_t(side * pageSize));
    ASSERT_EQ(pool.squareRanges.size(), 2u);
    EXPECT_FLOAT_EQ(pool.squareRanges[0].depthMin, 0.2f);
    EXPECT_NEAR(pool.squareRanges[0].depthStep, 0.1f / float(kVirtualPageDepthCodeMax), 1e-10f);
    EXPECT_FLOAT_EQ(pool.squareRanges[1].depthMin, 0.6f);
    EXPECT_EQ(pool.squareRanges[1].depthStep, 0.0f);
    // Texels (5, 0) and (4, 0): the right page's far and 0.6 (its whole range: code 0).
    EXPECT_EQ(pool.codes[5], kVirtualPageDepthCodeFar);
    EXPECT_EQ(pool.codes[4], 0u);
    for (uint32_t y = 0; y < pageSize; ++y)
        for (uint32_t x = 0; x < side; ++x) {
            const VirtualPageDepthRange& range = pool.squareRanges[x / pageSize];
            EXPECT_NEAR(virtualPoolDepth(pool.codes, side, x, y, range), texels[y * side + x], range.depthStep * 1.001f + 1e-7f)
                << x << ", " << y;
        }
    // Entries take the range of their physical page (a map whose pool starts at row 0, 2 pages a row).
    std::vector<gpu_data::VirtualPageEntry> entries(2, gpu_data::VirtualPageEntry{gpu_data::kVirtualPageNone, 0, 0, 0, 0, 0.0f, 0.0f, 0});
    entries[1].physicalPage = 1;
    setVirtualPageRanges(entries, pool, 2, 0);
    EXPECT_EQ(entries[0].depthMin, 0.0f) << "an entry holding no page keeps its range";
    EXPECT_EQ(entries[1].depthMin, 0.6f);
}

}  // namespace
}  // namespace penumbra
