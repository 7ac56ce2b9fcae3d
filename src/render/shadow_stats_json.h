#pragma once
// The shadow plan's stats as JSON for `--stats` and the viewer's stats panel (lights reserved, tiles,
// atlas occupancy, casters and triangles drawn per tile).
#include <cstdint>
#include <string>
#include <vector>

#include "shadows/shadow_planner.h"

namespace penumbra {

// What the GPU culling pass counted for one culling tile (directional tiles first, then spot/point).
struct CullTileCount {
    uint32_t casters = 0;
    uint64_t triangles = 0;
};

// gpuCounts: per culling tile, as the GPU drew it; null = the plan's own CPU caster lists (and no
// triangle counts: "trianglesPerTile" is left out).
std::string shadowStatsJson(const ShadowFrame& plan, const std::vector<CullTileCount>* gpuCounts = nullptr);
}
