#pragma once
// Tiling of the "other" (spot and point light) shadow atlas, after Catlike Coding "Spotlight Shadows" (Shadow
// Map Atlas, Dynamic Tiling): the atlas is split into split x split tiles with split = 1 for one tile, 2 for
// <= 4, 3 for <= 9, else 4 (the tutorial's code, not its prose, which says "8"). Tile i sits at column i %
// split, row i / split (row 0 = top). With more than one tile every tile keeps a 4-texel empty border: the
// caster pass draws through a scissor rect inset by 4 texels, so filters reading past a tile's edge find the
// cleared depth (lit) instead of a neighbour's shadows. One tile needs no border, viewport or scissor.
#include <cstdint>

#include <glm/glm.hpp>

#include "shadows/atlas_layout.h"

namespace penumbra {

inline constexpr uint32_t kMaxOtherShadowTiles = 16;  // 16 tiles in one atlas
inline constexpr uint32_t kOtherTileBorder = 4;       // texels, the scissor's inset

struct SpotAtlasLayout {
    uint32_t atlasSize = 0;
    uint32_t tileCount = 0;
    uint32_t split = 1;
    uint32_t tileSize = 0;  // atlasSize / split, rounded down (split 3 leaves a few texels unused)
    uint32_t border = 0;    // kOtherTileBorder when split > 1, else 0

    AtlasLayout asAtlasLayout() const { return {atlasSize, tileCount, split, tileSize}; }
};

SpotAtlasLayout makeSpotAtlasLayout(uint32_t atlasSize, uint32_t tileCount);

// The tile's viewport (the whole tile) and the scissor rect the casters are drawn through.
AtlasTileRect spotTileViewport(const SpotAtlasLayout& layout, uint32_t tileIndex);
AtlasTileRect spotTileScissor(const SpotAtlasLayout& layout, uint32_t tileIndex);

// Shadow clip space (Vulkan: y down, z in [0, 1]) -> atlas (u, v, depth) of one tile. Unlike the tutorial's
// tileScale = 1 / split, the scale is tileSize / atlasSize, so with split 3 the matrix lands exactly on
// the texels the viewport covered. Depth and w pass through: divide by w after applying it.
glm::mat4 spotAtlasFromClip(const SpotAtlasLayout& layout, uint32_t tileIndex);

// The atlas-uv rectangle (min u, min v, max u, max v) a filter of `reachTexels` may be centred in without
// reading outside the tile's drawn (scissored) interior.
glm::vec4 spotTileSampleBounds(const SpotAtlasLayout& layout, uint32_t tileIndex, float reachTexels);

}  // namespace penumbra
