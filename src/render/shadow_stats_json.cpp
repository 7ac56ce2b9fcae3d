#include "render/shadow_stats_json.h"

#include <nlohmann/json.hpp>

#include "other_shadow_structs.h"
#include "shadow_structs.h"

namespace penumbra {

static_assert(DirectionalShadowStats::kMaxLights == gpu_data::kMaxShadowedDirectionalLights);
static_assert(DirectionalShadowStats::kMaxCascades == gpu_data::kMaxCascades);
static_assert(OtherShadowStats::kMaxLights == gpu_data::kMaxShadowedOtherLights);
static_assert(OtherShadowStats::kMaxTiles == kMaxOtherShadowTiles);

namespace {

// The share of an atlas's area its tiles cover (0 for an atlas with no tile).
double occupancy(const AtlasLayout& atlas) {
    if (atlas.atlasSize == 0) return 0.0;
    const double side = double(atlas.atlasSize);
    return double(atlas.tileCount) * double(atlas.tileSize) * double(atlas.tileSize) / (side * side);
}

void fillDirectional(const ShadowFrame& plan, DirectionalShadowStats& stats) {
    const DirectionalShadowPlan& directional = plan.directional;
    stats.lightsConsidered = plan.stats.directionalLightsConsidered;
    stats.reservedLights.clear();
    for (const ReservedDirectionalLight& light : directional.lights) stats.reservedLights.push_back(light.sceneLightIndex);
    stats.atlasSize = directional.atlas.atlasSize;
    stats.tiles = directional.atlas.tileCount;
    stats.split = directional.atlas.split;
    stats.tileSize = directional.atlas.tileSize;
    stats.occupancy = occupancy(directional.atlas);
    stats.skippedByCascadeBlendCulling = plan.stats.skippedByBlendCulling;
    stats.skippedByReceiverCulling = plan.stats.skippedByReceiverCulling;
    stats.tightFit = directional.tight;
    stats.cullingSpheres.clear();
    stats.cascadeSplits.clear();
    for (const CascadeSphere& cascade : directional.cascades) {
        stats.cullingSpheres.push_back(glm::vec4(cascade.wsCenter, cascade.radius));
        stats.cascadeSplits.push_back(cascade.vsFar);
    }
    stats.tileStats.clear();
    for (const ShadowTile& tile : directional.tiles) {
        DirectionalTileStats t;
        t.light = tile.lightSlot;
        t.cascade = tile.cascadeIndex;
        t.drawn.casters = uint32_t(tile.casterInstances.size());
        t.depthRangeMetres = tile.nearDistance + tile.farDistance;
        t.pancakedDepthMetres = tile.pancakedDepth;
        t.texelSizeMetres = tile.wsTexelSize;
        t.worldFromClip = glm::inverse(tile.clipFromWorld);
        stats.tileStats.push_back(t);
    }
    stats.trianglesCounted = false;
}

void fillOther(const OtherShadowPlan& plan, OtherShadowStats& stats) {
    stats.lightsConsidered = plan.lightsConsidered;
    stats.reservedLights.clear();
    for (const ReservedOtherLight& light : plan.lights) stats.reservedLights.push_back(light.sceneLightIndex);
    stats.lightsDropped = uint32_t(plan.droppedLights.size());
    stats.droppedLights.clear();
    for (uint32_t light : plan.droppedLights) stats.droppedLights.push_back(light);
    stats.atlasSize = plan.atlas.atlasSize;
    stats.tiles = plan.atlas.tileCount;
    stats.split = plan.atlas.split;
    stats.tileSize = plan.atlas.tileSize;
    stats.tileBorder = plan.atlas.border;
    stats.occupancy = occupancy(plan.atlas.asAtlasLayout());
    stats.tileStats.clear();
    for (const ShadowTile& tile : plan.tiles) stats.tileStats.push_back({uint32_t(tile.casterInstances.size()), 0});
    stats.trianglesCounted = false;
}

const ShadowTileDraws& drawnOf(const DirectionalTileStats& tile) { return tile.drawn; }
const ShadowTileDraws& drawnOf(const ShadowTileDraws& tile) { return tile; }

template <typename Tiles>
nlohmann::json castersPerTile(const Tiles& tiles) {
    nlohmann::json counts = nlohmann::json::array();
    for (const auto& tile : tiles) counts.push_back(drawnOf(tile).casters);
    return counts;
}

template <typename Tiles>
nlohmann::json trianglesPerTile(const Tiles& tiles) {
    nlohmann::json counts = nlohmann::json::array();
    for (const auto& tile : tiles) counts.push_back(drawnOf(tile).triangles);
    return counts;
}

template <typename T, uint32_t N>
nlohmann::json array(const InlineList<T, N>& list) {
    return nlohmann::json(std::vector<T>(list.begin(), list.end()));
}

// The keys both atlases have: lights, layout, casters and triangles per tile.
template <typename AtlasStats>
nlohmann::json atlasJson(const AtlasStats& stats) {
    nlohmann::json json;
    json["lightsConsidered"] = stats.lightsConsidered;
    json["lightsReserved"] = stats.reservedLights.size();
    json["reservedLights"] = array(stats.reservedLights);  // the scene light of each slot (tile i: slot i / cascades)
    json["atlasSize"] = stats.atlasSize;
    json["tiles"] = stats.tiles;
    json["split"] = stats.split;
    json["tileSize"] = stats.tileSize;
    json["occupancy"] = stats.occupancy;
    json["castersPerTile"] = castersPerTile(stats.tileStats);
    json["casterDraws"] = casterDraws(stats);
    if (stats.trianglesCounted) json["trianglesPerTile"] = trianglesPerTile(stats.tileStats);
    return json;
}

nlohmann::json directionalJson(const DirectionalShadowStats& stats) {
    nlohmann::json json = atlasJson(stats);
    json["skippedByCascadeBlendCulling"] = stats.skippedByCascadeBlendCulling;
    json["skippedByReceiverCulling"] = stats.skippedByReceiverCulling;
    nlohmann::json spheres = nlohmann::json::array(), boxes = nlohmann::json::array();
    for (const glm::vec4& sphere : stats.cullingSpheres) spheres.push_back({sphere.x, sphere.y, sphere.z, sphere.w});
    std::vector<float> depthRange, pancakedDepth, texelSize;
    for (const DirectionalTileStats& tile : stats.tileStats) {
        const std::vector<float> matrix(&tile.worldFromClip[0][0], &tile.worldFromClip[0][0] + 16);  // column-major
        boxes.push_back({{"light", tile.light}, {"cascade", tile.cascade}, {"worldFromClip", matrix}});
        depthRange.push_back(tile.depthRangeMetres);
        pancakedDepth.push_back(tile.pancakedDepthMetres);
        texelSize.push_back(tile.texelSizeMetres);
    }
    json["cullingSpheres"] = spheres;
    json["tileBoxes"] = boxes;
    json["texelSizeMetres"] = texelSize;
    json["cascadeSplits"] = array(stats.cascadeSplits);
    json["fit"] = stats.tightFit ? "tight" : "sphere";
    json["depthRangeMetres"] = depthRange;
    json["pancakedDepthMetres"] = pancakedDepth;
    return json;
}

nlohmann::json otherJson(const OtherShadowStats& stats) {
    nlohmann::json json = atlasJson(stats);
    json["lightsDropped"] = stats.lightsDropped;
    json["droppedLights"] = array(stats.droppedLights);
    json["maxTiles"] = OtherShadowStats::kMaxTiles;
    json["tileBorder"] = stats.tileBorder;
    return json;
}

}  // namespace

uint32_t casterDraws(const DirectionalShadowStats& stats) {
    uint32_t total = 0;
    for (const DirectionalTileStats& tile : stats.tileStats) total += tile.drawn.casters;
    return total;
}

uint32_t casterDraws(const OtherShadowStats& stats) {
    uint32_t total = 0;
    for (const ShadowTileDraws& tile : stats.tileStats) total += tile.casters;
    return total;
}

void fillShadowPlanStats(const ShadowFrame& plan, ShadowPlanStats& stats) {
    fillDirectional(plan, stats.directional);
    fillOther(plan.other, stats.other);
    stats.shadowCasters = plan.stats.shadowCasters;
}

ShadowPlanStats shadowPlanStats(const ShadowFrame& plan) {
    ShadowPlanStats stats;
    fillShadowPlanStats(plan, stats);
    return stats;
}

void setGpuTileCounts(ShadowPlanStats& stats, std::span<const CullTileCount> counts) {
    DirectionalShadowStats& directional = stats.directional;
    OtherShadowStats& other = stats.other;
    directional.trianglesCounted = other.trianglesCounted = true;
    for (uint32_t tile = 0; tile < directional.tileStats.size() + other.tileStats.size(); ++tile) {
        const CullTileCount count = tile < counts.size() ? counts[tile] : CullTileCount{};
        ShadowTileDraws& drawn = tile < directional.tileStats.size() ? directional.tileStats[tile].drawn
                                                                     : other.tileStats[tile - directional.tileStats.size()];
        drawn = {count.casters, count.triangles};
    }
}

std::string toJson(const ShadowPlanStats& stats) {
    nlohmann::json json;
    json["directional"] = directionalJson(stats.directional);
    json["other"] = otherJson(stats.other);
    json["shadowCasters"] = stats.shadowCasters;
    return json.dump();
}

std::string shadowStatsJson(const ShadowFrame& plan, const std::vector<CullTileCount>* gpuCounts) {
    ShadowPlanStats stats = shadowPlanStats(plan);
    if (gpuCounts) setGpuTileCounts(stats, *gpuCounts);
    return toJson(stats);
}

}  // namespace penumbra
