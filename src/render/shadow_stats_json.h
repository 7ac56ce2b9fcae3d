#pragma once
// The shadow plan's stats as JSON for `--stats` (lights reserved, tiles, casters drawn per tile).
#include <string>

#include "shadows/shadow_planner.h"

namespace penumbra {
// castersPerCullTile: casters drawn per culling tile (directional tiles, then spot/point) as the GPU
// culling pass counted them; null = the plan's own CPU lists.
std::string shadowStatsJson(const ShadowFrame& plan, const std::vector<uint32_t>* castersPerCullTile = nullptr);
}
