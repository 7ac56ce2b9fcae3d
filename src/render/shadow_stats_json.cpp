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
    // Depth range per tile in metres (near + far distance) and how far casters reach in front of it.
    // World texel size per tile (the tight fit's gain shows here) and each cascade's split.
    std::vector<float> depthRange, pancakedDepth, texelSize, splits;
    for (const ShadowTile& tile : plan.directional.tiles) {
        depthRange.push_back(tile.nearDistance + tile.farDistance);
        pancakedDepth.push_back(tile.pancakedDepth);
        texelSize.push_back(tile.wsTexelSize);
    }
    for (const CascadeSphere& cascade : plan.directional.cascades) splits.push_back(cascade.vsFar);
    directional["texelSizeMetres"] = texelSize;
    directional["cascadeSplits"] = splits;
    directional["fit"] = plan.directional.tight ? "tight" : "sphere";
    directional["depthRangeMetres"] = depthRange;
    directional["pancakedDepthMetres"] = pancakedDepth;
    json["directional"] = directional;

    // Spot and point lights (seed 001): a spot light takes 1 tile, a point light 6, at most 16 tiles.
    const OtherShadowPlan& otherPlan = plan.other;
    nlohmann::json other;
    other["lightsConsidered"] = otherPlan.lightsConsidered;
    other["lightsReserved"] = otherPlan.lights.size();
    std::vector<uint32_t> reservedLights, castersPerTile;
    for (const ReservedOtherLight& light : otherPlan.lights) reservedLights.push_back(light.sceneLightIndex);
    uint32_t casterDraws = 0;
    for (const ShadowTile& tile : otherPlan.tiles) {
        castersPerTile.push_back(uint32_t(tile.casterInstances.size()));
        casterDraws += uint32_t(tile.casterInstances.size());
    }
    other["reservedLights"] = reservedLights;
    other["lightsDropped"] = otherPlan.droppedLights.size();
    other["droppedLights"] = otherPlan.droppedLights;
    other["atlasSize"] = otherPlan.atlas.atlasSize;
    other["tiles"] = otherPlan.atlas.tileCount;
    other["maxTiles"] = kMaxOtherShadowTiles;
    other["split"] = otherPlan.atlas.split;
    other["tileSize"] = otherPlan.atlas.tileSize;
    other["tileBorder"] = otherPlan.atlas.border;
    other["castersPerTile"] = castersPerTile;
    other["casterDraws"] = casterDraws;
    json["other"] = other;
    json["shadowCasters"] = stats.shadowCasters;
    return json.dump();
}

}  // namespace penumbra
