#include "render/shadow_stats_json.h"

#include <nlohmann/json.hpp>

namespace penumbra {

namespace {

// Casters per tile of `tiles`, the culling tiles from `first` on (GPU counts) or the CPU lists.
std::vector<uint32_t> castersPerTile(const std::vector<ShadowTile>& tiles, const std::vector<CullTileCount>* gpu, size_t first) {
    std::vector<uint32_t> counts;
    for (size_t i = 0; i < tiles.size(); ++i)
        counts.push_back(gpu && first + i < gpu->size() ? (*gpu)[first + i].casters : uint32_t(tiles[i].casterInstances.size()));
    return counts;
}

// Triangles drawn per tile of `tiles` as the GPU counted them (culling tiles from `first` on).
std::vector<uint64_t> trianglesPerTile(size_t tileCount, const std::vector<CullTileCount>& gpu, size_t first) {
    std::vector<uint64_t> counts;
    for (size_t i = 0; i < tileCount; ++i) counts.push_back(first + i < gpu.size() ? gpu[first + i].triangles : 0);
    return counts;
}

template <typename T>
T sum(const std::vector<T>& values) {
    T total = 0;
    for (T v : values) total += v;
    return total;
}

// The share of an atlas's area its tiles cover (0 for an atlas with no tile).
double occupancy(const AtlasLayout& atlas) {
    if (atlas.atlasSize == 0) return 0.0;
    const double side = double(atlas.atlasSize);
    return double(atlas.tileCount) * double(atlas.tileSize) * double(atlas.tileSize) / (side * side);
}

}  // namespace

std::string shadowStatsJson(const ShadowFrame& plan, const std::vector<CullTileCount>* gpuCounts) {
    const ShadowStats& stats = plan.stats;
    const size_t directionalTiles = plan.directional.tiles.size();
    const std::vector<uint32_t> directionalCasters = castersPerTile(plan.directional.tiles, gpuCounts, 0);
    const std::vector<uint32_t> otherCasters = castersPerTile(plan.other.tiles, gpuCounts, directionalTiles);
    nlohmann::json json;
    nlohmann::json directional;
    directional["lightsConsidered"] = stats.directionalLightsConsidered;
    directional["lightsReserved"] = stats.directionalLightsReserved;
    std::vector<uint32_t> reservedSuns;  // the scene light of each slot (tile i: slot i / cascades)
    for (const ReservedDirectionalLight& light : plan.directional.lights) reservedSuns.push_back(light.sceneLightIndex);
    directional["reservedLights"] = reservedSuns;
    directional["atlasSize"] = plan.directional.atlas.atlasSize;
    directional["tiles"] = plan.directional.atlas.tileCount;
    directional["split"] = plan.directional.atlas.split;
    directional["tileSize"] = plan.directional.atlas.tileSize;
    directional["occupancy"] = occupancy(plan.directional.atlas);
    directional["castersPerTile"] = directionalCasters;
    directional["casterDraws"] = sum(directionalCasters);
    if (gpuCounts) directional["trianglesPerTile"] = trianglesPerTile(directionalTiles, *gpuCounts, 0);
    directional["skippedByCascadeBlendCulling"] = stats.skippedByBlendCulling;
    // Depth range per tile in metres (near + far distance) and how far casters reach in front of it.
    // World texel size per tile (the tight fit's gain shows here) and each cascade's split.
    std::vector<float> depthRange, pancakedDepth, texelSize, splits;
    for (const ShadowTile& tile : plan.directional.tiles) {
        depthRange.push_back(tile.nearDistance + tile.farDistance);
        pancakedDepth.push_back(tile.pancakedDepth);
        texelSize.push_back(tile.wsTexelSize);
    }
    // The culling spheres (x, y, z, radius) and each tile's worldFromClip box, for debug views that draw them.
    nlohmann::json spheres = nlohmann::json::array(), boxes = nlohmann::json::array();
    for (const CascadeSphere& cascade : plan.directional.cascades) {
        splits.push_back(cascade.vsFar);
        spheres.push_back({cascade.wsCenter.x, cascade.wsCenter.y, cascade.wsCenter.z, cascade.radius});
    }
    for (const ShadowTile& tile : plan.directional.tiles) {
        const glm::mat4 worldFromClip = glm::inverse(tile.clipFromWorld);
        std::vector<float> matrix(&worldFromClip[0][0], &worldFromClip[0][0] + 16);  // column-major
        boxes.push_back({{"light", tile.lightSlot}, {"cascade", tile.cascadeIndex}, {"worldFromClip", matrix}});
    }
    directional["cullingSpheres"] = spheres;
    directional["tileBoxes"] = boxes;
    directional["texelSizeMetres"] = texelSize;
    directional["cascadeSplits"] = splits;
    directional["fit"] = plan.directional.tight ? "tight" : "sphere";
    directional["depthRangeMetres"] = depthRange;
    directional["pancakedDepthMetres"] = pancakedDepth;
    json["directional"] = directional;

    // Spot and point lights: a spot light takes 1 tile, a point light 6, at most 16 tiles.
    const OtherShadowPlan& otherPlan = plan.other;
    nlohmann::json other;
    other["lightsConsidered"] = otherPlan.lightsConsidered;
    other["lightsReserved"] = otherPlan.lights.size();
    std::vector<uint32_t> reservedLights;
    for (const ReservedOtherLight& light : otherPlan.lights) reservedLights.push_back(light.sceneLightIndex);
    other["reservedLights"] = reservedLights;
    other["lightsDropped"] = otherPlan.droppedLights.size();
    other["droppedLights"] = otherPlan.droppedLights;
    other["atlasSize"] = otherPlan.atlas.atlasSize;
    other["tiles"] = otherPlan.atlas.tileCount;
    other["maxTiles"] = kMaxOtherShadowTiles;
    other["split"] = otherPlan.atlas.split;
    other["tileSize"] = otherPlan.atlas.tileSize;
    other["tileBorder"] = otherPlan.atlas.border;
    other["occupancy"] = occupancy(otherPlan.atlas.asAtlasLayout());
    other["castersPerTile"] = otherCasters;
    other["casterDraws"] = sum(otherCasters);
    if (gpuCounts) other["trianglesPerTile"] = trianglesPerTile(plan.other.tiles.size(), *gpuCounts, directionalTiles);
    json["other"] = other;
    json["shadowCasters"] = stats.shadowCasters;
    return json.dump();
}

}  // namespace penumbra
