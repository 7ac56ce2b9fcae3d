#pragma once
// The shadow plan's stats as JSON for `--stats` (lights reserved, tiles, casters drawn per tile).
#include <string>

#include "shadows/shadow_planner.h"

namespace penumbra {
std::string shadowStatsJson(const ShadowFrame& plan);
}
