#pragma once
// Tiling of the directional shadow atlas (Catlike Coding "Directional Shadows": Multiple Lights, Rendering
// Cascades): tiles = lights x cascades in a split x split grid, tile i at column i % split, row i / split
// (row 0 = top, pixel y = 0).
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra {

struct AtlasTileRect {
    glm::uvec2 offset{0u};  // top-left pixel of the tile in the atlas (Vulkan viewport / scissor)
    uint32_t size = 0;      // width = height in pixels
};

struct AtlasLayout {
    uint32_t atlasSize = 0;
    uint32_t tileCount = 0;
    uint32_t split = 1;  // 1 for <= 1 tile, 2 for <= 4, else 4
    uint32_t tileSize = 0;
};

AtlasLayout makeAtlasLayout(uint32_t atlasSize, uint32_t tileCount);
AtlasTileRect tileRect(const AtlasLayout& layout, uint32_t tileIndex);

// Maps shadow clip space (Vulkan: y down, z in [0, 1]) to atlas (u, v, depth): uv = ndc * 0.5 + 0.5 inside
// the tile, then scaled by tileSize / atlasSize and offset to the tile (ConvertToAtlasMatrix of "Directional
// Shadows", Shadow Matrices, as one matrix product instead of its per-element edit). Depth and w pass through
// unchanged.
glm::mat4 atlasFromClip(const AtlasLayout& layout, uint32_t tileIndex);

}  // namespace penumbra
