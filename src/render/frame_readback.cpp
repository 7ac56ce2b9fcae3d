#include "render/frame_readback.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "core/error.h"
#include "cull_structs.h"
#include "light_cluster_structs.h"
#include "virtual_page_structs.h"
#include "render/shadow_stats_json.h"

namespace penumbra {

const uint8_t* readbackPiece(const std::vector<uint8_t>& readback, uint64_t offset, uint64_t bytes) {
    if (offset == FrameReadbackLayout::kAbsent) return nullptr;
    const bool inside = offset <= readback.size() && bytes <= readback.size() - offset;
    PENUMBRA_ASSERT(inside);
    return inside ? readback.data() + offset : nullptr;
}

namespace {

// Copies `count` values of T from `offset`; false where the piece is absent.
template <typename T>
bool readPiece(const std::vector<uint8_t>& readback, uint64_t offset, T* values, size_t count = 1) {
    const uint8_t* piece = readbackPiece(readback, offset, count * sizeof(T));
    if (piece) std::memcpy(values, piece, count * sizeof(T));
    return piece != nullptr;
}

void applyCullTiles(FrameStats& stats, const ShadowFrame& plan, const FrameReadbackLayout& layout,
                    const std::vector<uint8_t>& readback) {
    const size_t directionalTiles = plan.directional.tiles.size();
    constexpr size_t kMaxCullTiles = DirectionalShadowStats::kMaxTiles + OtherShadowStats::kMaxTiles;
    const size_t tileCount = std::min(directionalTiles + plan.other.tiles.size(), kMaxCullTiles);
    std::array<gpu_data::CullTileStats, kMaxCullTiles> tiles{};
    if (tileCount > 0) readPiece(readback, layout.cullTiles, tiles.data(), tileCount);  // else zero counts
    std::array<CullTileCount, kMaxCullTiles> counts{};
    for (size_t i = 0; i < tileCount; ++i) {
        const size_t atlasIndex = i < directionalTiles ? 0 : 1;
        if (atlasIndex < stats.atlases.size()) {
            stats.atlases[atlasIndex].draws += tiles[i].draws;
            stats.atlases[atlasIndex].triangles += tiles[i].triangles;
        }
        counts[i] = {tiles[i].instances, tiles[i].triangles};
    }
    fillShadowPlanStats(plan, stats.shadows);
    setGpuTileCounts(stats.shadows, std::span<const CullTileCount>(counts.data(), tileCount));
}

void applyRasterCounters(FrameStats& stats, const FrameReadbackLayout& layout, const std::vector<uint8_t>& readback,
                         glm::uvec3& rasterNeeded) {
    for (uint64_t offset : layout.rasterCounters) {
        gpu_data::RasterCounters counters{};
        if (!readPiece(readback, offset, &counters)) continue;
        stats.rasterWorkItems += counters.workQueued;
        stats.rasterSimplifiedItems += counters.lodItems;
        stats.rasterMediumTriangles += counters.mediumQueued;
        stats.rasterLargeTriangles += counters.largeQueued;
        stats.rasterChunks += counters.chunksQueued;
        stats.rasterDropped += uint64_t(counters.largeDropped) + counters.chunksDropped + counters.workDropped;
        stats.shadowMeshletsOutside += counters.meshletsOutside;
        rasterNeeded = glm::max(rasterNeeded, glm::uvec3(counters.largeQueued, counters.chunksQueued, counters.workQueued));
    }
    if (stats.rasterDropped > 0)
        stats.warnings.push_back("the compute rasterizer's queues were full: " + std::to_string(stats.rasterDropped) +
                                 " large pieces, chunks or work items were not drawn in frame " + std::to_string(stats.frameIndex) +
                                 "; the queues grow for the next frames");
}

void applyViewCulling(FrameStats& stats, const FrameReadbackLayout& layout, const std::vector<uint8_t>& readback) {
    gpu_data::CullTileStats lists[2]{};
    if (readPiece(readback, layout.viewLists, lists, 2)) {
        stats.viewInstancesEarly = lists[0].instances;
        stats.viewInstancesLate = lists[1].instances;
        stats.viewTriangles = uint64_t(lists[0].triangles) + lists[1].triangles;
    }
    glm::uvec4 meshlets{0u};
    if (readPiece(readback, layout.viewMeshlets, &meshlets)) {
        stats.viewMeshletsOutside = meshlets.x;
        stats.viewMeshletsFacingAway = meshlets.y;
    }
}

void applyLightClusters(FrameStats& stats, const FrameReadbackLayout& layout, const std::vector<uint8_t>& readback) {
    gpu_data::LightClusterStats counts{};
    if (!readPiece(readback, layout.lightClusters, &counts)) return;
    stats.lightsPerClusterMean = double(counts.lightBits) / double(gpu_data::kClusterCount);
    stats.lightsPerClusterMax = counts.mostLightsInACluster;
}

void addPageStats(VirtualPageCounts& pages, const gpu_data::VirtualPageStats& counts) {
    pages.requested += counts.requested;
    pages.cached += counts.cached;
    pages.allocated += counts.allocated;
    pages.drawn += counts.toDraw;
    pages.evicted += counts.evicted;
    pages.overflowed += counts.overflowed;
    pages.deferred += counts.deferred;
    pages.resident += counts.resident;
}

void readLevels(FrameStats::VirtualMapLevels& levels, const std::vector<uint8_t>& readback, uint64_t offset,
                uint32_t levelCount) {
    gpu_data::VirtualPageLevelStats counts{};
    levels = {};
    if (!readPiece(readback, offset, &counts)) return;
    levels.levelCount = std::min<uint32_t>(levelCount, uint32_t(levels.requested.size()));
    for (uint32_t level = 0; level < levels.levelCount; ++level) {
        levels.requested[level] = counts.requested[level];
        levels.cached[level] = counts.cached[level];
        levels.drawn[level] = counts.drawn[level];
    }
}

// The maps' page counts, summed, and the faces'; maps and poolPages were set when the frame was recorded.
void applyVirtualPages(FrameStats& stats, const FrameReadbackLayout& layout, const std::vector<uint8_t>& readback) {
    VirtualPageCounts& pages = stats.virtualPages;
    for (uint64_t offset : layout.virtualPages) {
        gpu_data::VirtualPageStats counts{};
        if (readPiece(readback, offset, &counts)) addPageStats(pages, counts);
    }
    for (size_t map = 0; map < stats.virtualMaps.size(); ++map)
        readLevels(stats.virtualMaps[map], readback, layout.virtualLevels[map], layout.virtualLevelCount);
    gpu_data::VirtualPageStats faceCounts{};
    if (readPiece(readback, layout.virtualFacePages, &faceCounts)) addPageStats(stats.virtualFacePages, faceCounts);
    readLevels(stats.virtualFaceMips, readback, layout.virtualFaceMips, layout.virtualFaceMipCount);
    const auto warn = [&](uint32_t overflowed, const char* key) {
        if (overflowed > 0)
            stats.warnings.push_back("virtual shadow maps: " + std::to_string(overflowed) +
                                     " requested pages found no free physical page (raise shadows.virtual." + key +
                                     "); a coarser level served them");
    };
    warn(pages.overflowed, "poolPages");
    warn(stats.virtualFacePages.overflowed, "facePoolPages");
}

}  // namespace

void applyFrameReadback(FrameStats& stats, const ShadowFrame& plan, const FrameReadbackLayout& layout,
                        const std::vector<uint8_t>& readback, glm::uvec3& rasterNeeded) {
    applyCullTiles(stats, plan, layout, readback);
    applyRasterCounters(stats, layout, readback, rasterNeeded);
    applyViewCulling(stats, layout, readback);
    applyLightClusters(stats, layout, readback);
    applyVirtualPages(stats, layout, readback);
}

double timedMilliseconds(const FrameStats& stats, std::initializer_list<const char*> names) {
    double total = 0.0;
    for (const PassTiming& timing : stats.gpuTimings)
        for (const char* name : names)
            if (timing.name == name) total += timing.milliseconds;
    return total;
}

}  // namespace penumbra
