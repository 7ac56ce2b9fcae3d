#pragma once
// What the GPU counts during a frame and the renderer reads back once the frame is done
// (gpu::Device::readBackAtFrameEnd): where each piece lies in the frame's readback, and how the pieces
// become the frame's FrameStats. No GPU here: the decoding is tested on plain bytes.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/renderer.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// Byte offsets in CompletedFrame::readback, as readBackAtFrameEnd returned them; kAbsent where the
// frame did not read that piece back.
struct FrameReadbackLayout {
    static constexpr uint64_t kAbsent = ~0ull;
    uint64_t cullTiles = kAbsent;                       // CullTileStats per shadow tile, directional first
    // RasterCounters of the directional and spot/point atlas, then of each directional virtual map's pages,
    // then of the spot and point lights' faces' pages.
    uint64_t rasterCounters[7] = {kAbsent, kAbsent, kAbsent, kAbsent, kAbsent, kAbsent, kAbsent};
    uint64_t visibleSurfaces = kAbsent;                 // the tight fit's depth-bin bounds (VisibleSurfacePass)
    uint64_t viewLists = kAbsent;                       // 2 CullTileStats: the main view's early and late lists
    uint64_t viewMeshlets = kAbsent;                    // uvec4: visibility-buffer meshlets outside, facing away
    uint64_t lightClusters = kAbsent;                   // LightClusterStats
    uint64_t virtualPages[4] = {kAbsent, kAbsent, kAbsent, kAbsent};  // VirtualPageStats per directional map
    uint64_t virtualLevels[4] = {kAbsent, kAbsent, kAbsent, kAbsent};  // VirtualPageLevelStats per directional map
    uint32_t virtualLevelCount = 0;                                     // levels of every map
    uint64_t virtualFacePages = kAbsent;   // VirtualPageStats of the spot and point lights' faces
    uint64_t virtualFaceMips = kAbsent;    // VirtualPageLevelStats of them, per mip (the table's buckets)
    uint32_t virtualFaceMipCount = 0;
};

// The `bytes` bytes at `offset` in a frame's readback; null where the piece is absent. A piece beyond
// the readback is an internal error (the layout and the readback come from one frame): asserted, null.
const uint8_t* readbackPiece(const std::vector<uint8_t>& readback, uint64_t offset, uint64_t bytes);

// Fills `stats` from the pieces `layout` names: casters and triangles per atlas and the shadow stats JSON
// (from the plan, with the GPU's counts where they came back), the compute rasterizer's counters (and a
// warning when its queues overflowed), the main view's culling, the light clusters' counts and the
// virtual shadow maps' pages (a warning when a pool overflowed).
// `rasterNeeded` grows to the most large pieces (x), chunks (y) and work items (z) one raster pass asked for.
void applyFrameReadback(FrameStats& stats, const ShadowFrame& plan, const FrameReadbackLayout& layout,
                        const std::vector<uint8_t>& readback, glm::uvec3& rasterNeeded);

// The sum of the GPU timings with these names (0 for names the frame did not time).
double timedMilliseconds(const FrameStats& stats, std::initializer_list<const char*> names);

}  // namespace penumbra
