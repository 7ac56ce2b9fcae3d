// Cached shadow tiles (render/tile_cache.h): which tiles a frame draws again.
#include <gtest/gtest.h>

#include "render/tile_cache.h"

namespace penumbra {
namespace {

std::vector<TileSignature> tiles(std::initializer_list<float> firstValues) {
    std::vector<TileSignature> result;
    for (float v : firstValues) {
        TileSignature signature;
        for (float value : {v, 1.0f, 2.0f}) signature.push_back(value);
        result.push_back(signature);
    }
    return result;
}

TEST(TileCache, FirstFrameDrawsEveryTile) {
    TileCache cache;
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2, 3}), 0, false, 0, true), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(cache.reused(), 0u);
}

TEST(TileCache, UnchangedTilesAreKept) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2, 3}), 0, false, 0, true);
    EXPECT_TRUE(cache.tilesToDraw(tiles({1, 2, 3}), 0, false, 0, true).empty());
    EXPECT_EQ(cache.reused(), 3u);
}

TEST(TileCache, OnlyTheChangedTileIsDrawn) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2, 3}), 0, false, 0, true);
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 5, 3}), 0, false, 0, true), (std::vector<uint32_t>{1}));
    EXPECT_EQ(cache.reused(), 2u);
}

TEST(TileCache, NewTilesAreDrawn) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2}), 0, false, 0, true);
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2, 3}), 0, false, 0, true), (std::vector<uint32_t>{2}));
}

TEST(TileCache, ARemadeAtlasChangedCastersOrAnotherRasterizerDrawEverything) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2}), 0, false, 0, true);
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2}), 1, false, 0, true).size(), 2u);  // atlas re-made
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2}), 1, false, 7, true).size(), 2u);  // casters changed
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2}), 1, true, 7, true).size(), 2u);   // compute rasterizer now
    EXPECT_TRUE(cache.tilesToDraw(tiles({1, 2}), 1, true, 7, true).empty());
}

TEST(TileCache, DisabledCachingDrawsEveryFrameInFull) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2}), 0, false, 0, false);
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2}), 0, false, 0, false).size(), 2u);
}

TEST(TileCache, InvalidateDrawsEverythingOnce) {
    TileCache cache;
    cache.tilesToDraw(tiles({1, 2}), 0, false, 0, true);
    cache.invalidate();
    EXPECT_EQ(cache.tilesToDraw(tiles({1, 2}), 0, false, 0, true).size(), 2u);
    EXPECT_TRUE(cache.tilesToDraw(tiles({1, 2}), 0, false, 0, true).empty());
}

TEST(TileSignatures, DirectionalTilesDependOnTheCascadeSpheres) {
    ShadowTile tile;
    DirectionalShadowPlan plan;
    CascadeSphere sphere;
    sphere.radius = 5.0f;
    plan.cascades = {sphere};
    const TileSignature a = directionalTileSignature(tile, plan);
    plan.cascades[0].radius = 6.0f;
    EXPECT_NE(directionalTileSignature(tile, plan), a);
    EXPECT_EQ(otherTileSignature(tile), otherTileSignature(tile));
    tile.clipFromWorld[3][0] = 0.5f;
    EXPECT_NE(directionalTileSignature(tile, plan), a);
}

}  // namespace
}  // namespace penumbra
