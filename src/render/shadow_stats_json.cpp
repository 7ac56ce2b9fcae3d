#include "render/shadow_stats_json.h"

#include <nlohmann/json.hpp>

namespace penumbra {

std::string shadowStatsJson(const ShadowFrame& plan) {
    const ShadowStats& stats = plan.stats;
    nlohmann::json json;
    nlohmann::json directional;
    directional["lightsConsidered"] = stats.directionalLightsConsidered;
    directional["lightsReserved"] = stats.directionalLightsReserved;
    directional["atlasSize"] = plan.directional.atlas.atlasSize;
    directional["tiles"] = plan.directional.atlas.tileCount;
    directional["split"] = plan.directional.atlas.split;
    directional["tileSize"] = plan.directional.atlas.tileSize;
    directional["castersPerTile"] = stats.castersPerTile;
    directional["casterDraws"] = stats.casterDraws;
    directional["skippedByCascadeBlendCulling"] = stats.skippedByBlendCulling;
    json["directional"] = directional;
    json["shadowCasters"] = stats.shadowCasters;
    return json.dump();
}

}  // namespace penumbra
