// The spot/point atlas tiling (Catlike Coding "Spotlight Shadows": Shadow Map Atlas, Dynamic Tiling).
#include <gtest/gtest.h>

#include "shadows/spot_atlas_layout.h"

using namespace penumbra;

TEST(SpotAtlasLayout, SplitFollowsTheTileCountTable) {
    // The tutorial's code: 1 tile -> 1, <= 4 -> 2, <= 9 -> 3, else 4.
    const uint32_t expected[17] = {1, 1, 2, 2, 2, 3, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4};
    for (uint32_t count = 0; count <= 16; ++count) {
        const SpotAtlasLayout layout = makeSpotAtlasLayout(1024, count);
        EXPECT_EQ(layout.split, expected[count]) << count << " tiles";
        EXPECT_EQ(layout.tileSize, 1024u / expected[count]) << count << " tiles";
    }
}

TEST(SpotAtlasLayout, OneTileUsesTheWholeAtlasWithoutBorder) {
    const SpotAtlasLayout layout = makeSpotAtlasLayout(512, 1);
    EXPECT_EQ(layout.border, 0u);
    const AtlasTileRect scissor = spotTileScissor(layout, 0);
    EXPECT_EQ(scissor.offset, glm::uvec2(0u));
    EXPECT_EQ(scissor.size, 512u);
}

TEST(SpotAtlasLayout, TilesAreDisjointInsideTheAtlasWithAFourTexelScissorBorder) {
    for (uint32_t count = 2; count <= 16; ++count) {
        const SpotAtlasLayout layout = makeSpotAtlasLayout(1024, count);
        ASSERT_EQ(layout.border, 4u);
        for (uint32_t i = 0; i < count; ++i) {
            const AtlasTileRect tile = spotTileViewport(layout, i);
            const AtlasTileRect scissor = spotTileScissor(layout, i);
            EXPECT_LE(tile.offset.x + tile.size, 1024u);
            EXPECT_LE(tile.offset.y + tile.size, 1024u);
            EXPECT_EQ(scissor.offset, tile.offset + glm::uvec2(4u));
            EXPECT_EQ(scissor.size, tile.size - 8u);
            for (uint32_t j = 0; j < i; ++j) {
                const AtlasTileRect other = spotTileViewport(layout, j);
                const bool apart = tile.offset.x >= other.offset.x + other.size || other.offset.x >= tile.offset.x + tile.size ||
                                   tile.offset.y >= other.offset.y + other.size || other.offset.y >= tile.offset.y + tile.size;
                EXPECT_TRUE(apart) << "tiles " << i << " and " << j << " of " << count;
            }
        }
    }
}

TEST(SpotAtlasLayout, AtlasMatrixMapsClipCornersOntoTheTileCornersAfterTheDivide) {
    // split 3 on 1000 texels: tiles of 333 texels, the matrix must follow them exactly (not 1/3).
    const SpotAtlasLayout layout = makeSpotAtlasLayout(1000, 5);
    ASSERT_EQ(layout.tileSize, 333u);
    const glm::mat4 m = spotAtlasFromClip(layout, 4);  // column 1, row 1
    const float w = 2.5f;  // a perspective clip position: everything scaled by w
    const glm::vec4 topLeft = m * glm::vec4(-w, -w, 0.3f * w, w);
    const glm::vec4 bottomRight = m * glm::vec4(w, w, 0.7f * w, w);
    EXPECT_NEAR(topLeft.x / topLeft.w, 333.0f / 1000.0f, 1e-6f);
    EXPECT_NEAR(topLeft.y / topLeft.w, 333.0f / 1000.0f, 1e-6f);
    EXPECT_NEAR(topLeft.z / topLeft.w, 0.3f, 1e-6f);
    EXPECT_NEAR(bottomRight.x / bottomRight.w, 666.0f / 1000.0f, 1e-6f);
    EXPECT_NEAR(bottomRight.y / bottomRight.w, 666.0f / 1000.0f, 1e-6f);
    EXPECT_NEAR(bottomRight.z / bottomRight.w, 0.7f, 1e-6f);
}

TEST(SpotAtlasLayout, SampleBoundsStayInsideTheScissorByTheFilterReach) {
    const SpotAtlasLayout layout = makeSpotAtlasLayout(1024, 4);
    const glm::vec4 bounds = spotTileSampleBounds(layout, 3, 3.0f);  // tile at (512, 512), 512 texels
    EXPECT_FLOAT_EQ(bounds.x * 1024.0f, 512.0f + 4.0f + 3.0f);
    EXPECT_FLOAT_EQ(bounds.y * 1024.0f, 512.0f + 4.0f + 3.0f);
    EXPECT_FLOAT_EQ(bounds.z * 1024.0f, 1024.0f - 4.0f - 3.0f);
    EXPECT_FLOAT_EQ(bounds.w * 1024.0f, 1024.0f - 4.0f - 3.0f);
}
