#include <gtest/gtest.h>

#include "shadows/atlas_layout.h"
#include "shadows/cascades.h"

using namespace penumbra;

TEST(AtlasLayout, SplitIsOneTwoOrFourByTileCount) {
    EXPECT_EQ(makeAtlasLayout(1024, 0).split, 1u);
    EXPECT_EQ(makeAtlasLayout(1024, 1).split, 1u);
    EXPECT_EQ(makeAtlasLayout(1024, 2).split, 2u);
    EXPECT_EQ(makeAtlasLayout(1024, 4).split, 2u);
    EXPECT_EQ(makeAtlasLayout(1024, 5).split, 4u);
    EXPECT_EQ(makeAtlasLayout(1024, 16).split, 4u);
    EXPECT_EQ(makeAtlasLayout(2048, 8).tileSize, 512u);
}

TEST(AtlasLayout, TileRectsFillRowsLeftToRightFromTheTop) {
    const AtlasLayout layout = makeAtlasLayout(1024, 16);
    EXPECT_EQ(tileRect(layout, 0).offset, glm::uvec2(0, 0));
    EXPECT_EQ(tileRect(layout, 3).offset, glm::uvec2(768, 0));
    EXPECT_EQ(tileRect(layout, 6).offset, glm::uvec2(512, 256));
    EXPECT_EQ(tileRect(layout, 15).offset, glm::uvec2(768, 768));
    EXPECT_EQ(tileRect(layout, 6).size, 256u);
}

namespace {

// A light shining straight down on a tile centred at the origin with half-extent 8: light-space x is
// world -x and light-space y (up, toward the top of the tile) is world +z.
glm::mat4 downLightClipFromWorld() {
    return orthoClipFromLight(8.0f, 20.0f, 8.0f) * lightRotationFromWorld(glm::vec3(0.0f, -1.0f, 0.0f));
}

glm::vec3 atlasTexel(const AtlasLayout& layout, uint32_t tile, glm::vec3 wsPoint) {
    const glm::vec4 atlas = atlasFromClip(layout, tile) * downLightClipFromWorld() * glm::vec4(wsPoint, 1.0f);
    return {atlas.x * float(layout.atlasSize), atlas.y * float(layout.atlasSize), atlas.z};
}

}  // namespace

TEST(AtlasFromWorld, MapsAWorldPointToItsTexelInASingleTile) {
    const AtlasLayout layout = makeAtlasLayout(1024, 1);
    // World (-4, 0, 4): light-space (4, 4) = three quarters right, one quarter down the tile.
    const glm::vec3 texel = atlasTexel(layout, 0, {-4.0f, 0.0f, 4.0f});
    EXPECT_NEAR(texel.x, 768.0f, 1e-3f);
    EXPECT_NEAR(texel.y, 256.0f, 1e-3f);
    EXPECT_NEAR(texel.z, 20.0f / 28.0f, 1e-5f);  // 20 below the near plane of a 28-deep box
}

TEST(AtlasFromWorld, MapsAWorldPointToItsTexelInSplitTwo) {
    const AtlasLayout layout = makeAtlasLayout(1024, 4);  // 2 x 2 tiles of 512
    const glm::vec3 texel = atlasTexel(layout, 3, {-4.0f, 0.0f, 4.0f});
    EXPECT_NEAR(texel.x, 512.0f + 384.0f, 1e-3f);
    EXPECT_NEAR(texel.y, 512.0f + 128.0f, 1e-3f);
}

TEST(AtlasFromWorld, MapsAWorldPointToItsTexelInSplitFour) {
    const AtlasLayout layout = makeAtlasLayout(2048, 16);  // 4 x 4 tiles of 512
    const glm::vec3 texel = atlasTexel(layout, 6, {8.0f, 0.0f, -8.0f});  // bottom-left corner of tile (2, 1)
    EXPECT_NEAR(texel.x, 1024.0f, 1e-3f);
    EXPECT_NEAR(texel.y, 1024.0f, 1e-3f);
}
