#pragma once
// The shadow plan's stats (penumbra/shadow_stats.h) from a ShadowFrame, without touching the heap, and
// as JSON for `--stats` (toJson, declared in the public header).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "penumbra/shadow_stats.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// What the GPU culling pass counted for one culling tile (directional tiles first, then spot/point).
struct CullTileCount {
    uint32_t casters = 0;
    uint64_t triangles = 0;
};

// The plan's stats into `stats` (overwritten), casters per tile from the plan's CPU lists.
void fillShadowPlanStats(const ShadowFrame& plan, ShadowPlanStats& stats);
ShadowPlanStats shadowPlanStats(const ShadowFrame& plan);
// The culling tiles (directional tiles first, then spot/point) as the GPU drew them; a tile past the
// end of `counts` drew nothing. Both atlases then count triangles.
void setGpuTileCounts(ShadowPlanStats& stats, std::span<const CullTileCount> counts);

// toJson(shadowPlanStats(plan)) with the GPU's counts per culling tile when given (null: the plan's own
// CPU caster lists and no "trianglesPerTile").
std::string shadowStatsJson(const ShadowFrame& plan, const std::vector<CullTileCount>* gpuCounts = nullptr);

}  // namespace penumbra
