#pragma once
// The virtual shadow map pool's depth codes on the CPU (shaders/shared/virtual_page_structs.h, "The pool's
// texels"): what virtual_page_copy.comp stores when it copies a drawn page into the pool, for tests and
// tools that build or read pools without a GPU. Each page keeps 16-bit codes relative to its own depth
// range; its entry holds the range that decodes them.
#include <cstdint>
#include <span>
#include <vector>

#include "virtual_page_structs.h"

namespace penumbra {

// What a page's entry holds to decode its codes.
struct VirtualPageDepthRange {
    float depthMin = 1.0f;   // the nearest drawn depth (1: nothing drawn)
    float depthStep = 0.0f;  // (farthest - nearest) / kVirtualPageDepthCodeMax
};

// The range of a page's depths: those nearer than far (< 1; negatives count as 0, as drawn).
VirtualPageDepthRange virtualPageDepthRange(std::span<const float> depths);
// The code of `depth` in a page of `range`: far for depth >= 1, else rounded up (it never decodes nearer).
uint32_t virtualPageDepthCode(float depth, const VirtualPageDepthRange& range);

// A pool of float depths, `poolSide` texels a row, as the pool texture's codes (an R16_UNORM texture's
// texels as they are; an R32_SFLOAT one holds virtualPageTexelOfCode of each), each pageSize^2 square of it
// (its pages, of every map that shares it) encoded with its own range.
struct VirtualPoolCodes {
    std::vector<uint16_t> codes;
    std::vector<VirtualPageDepthRange> squareRanges;  // by square: (row / pageSize) * (poolSide / pageSize) + column / pageSize
    uint32_t poolSide = 0, pageSize = 0;
};
VirtualPoolCodes encodeVirtualPool(std::span<const float> texels, uint32_t poolSide, uint32_t pageSize);

// Sets the range of every resident entry of a map whose pool lies from row poolOriginY of `pool`
// (poolPagesPerSide^2 physical pages) to its physical page's, as the copy pass does when it draws the page.
void setVirtualPageRanges(std::span<gpu_data::VirtualPageEntry> entries, const VirtualPoolCodes& pool,
                          uint32_t poolPagesPerSide, uint32_t poolOriginY);

// A pool texture's bytes holding `codes`, bytesPerTexel 2 (R16_UNORM: the codes) or 4 (R32_SFLOAT:
// virtualPageTexelOfCode of each), and the codes back from such bytes.
std::vector<uint8_t> virtualPoolTexelBytes(std::span<const uint16_t> codes, uint32_t bytesPerTexel);
std::vector<uint16_t> virtualPoolCodesOfBytes(std::span<const uint8_t> bytes, uint32_t bytesPerTexel);

// The stored depth of texel (x, y) of a pool texture's codes, `codesPerRow` a row, in a page of `range`.
float virtualPoolDepth(std::span<const uint16_t> codes, uint32_t codesPerRow, uint32_t x, uint32_t y,
                       const VirtualPageDepthRange& range);

}  // namespace penumbra
