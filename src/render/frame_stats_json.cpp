// toJson(FrameStats): what `penumbra render --stats` and the Python package's frame stats hold.
#include <nlohmann/json.hpp>

#include "penumbra/renderer.h"

namespace penumbra {

std::string toJson(const FrameStats& frame) {
    nlohmann::json stats;
    nlohmann::json gpuMs = nlohmann::json::object();
    for (const auto& timing : frame.gpuTimings) gpuMs[timing.name] = timing.milliseconds;
    stats["gpuMs"] = gpuMs;
    stats["cpuPlanMs"] = frame.cpu.plan + frame.cpu.culling;
    stats["cpuMs"] = {{"plan", frame.cpu.plan}, {"culling", frame.cpu.culling}, {"upload", frame.cpu.upload},
                      {"record", frame.cpu.record}, {"submit", frame.cpu.submit},
                      {"readback", frame.cpu.readback}, {"thread", frame.cpu.thread}};
    stats["shadows"] = nlohmann::json::parse(toJson(frame.shadows));
    stats["warnings"] = frame.warnings;
    stats["shadowRaster"] = {{"used", frame.shadowRaster},
                             {"choice", frame.shadowRasterChoice},
                             {"workItems", frame.rasterWorkItems},
                             {"simplifiedItems", frame.rasterSimplifiedItems}};
    stats["directionalShadows"] = frame.directionalShadows;
    stats["spotShadows"] = frame.spotShadows;
    stats["tightFitWaited"] = frame.tightFitWaited;
    stats["mainView"] = {{"used", frame.mainView},
                         {"choice", frame.mainViewChoice},
                         {"instances", frame.viewInstances},
                         {"drawnEarly", frame.viewInstancesEarly},
                         {"drawnLate", frame.viewInstancesLate},
                         {"triangles", frame.viewTriangles}};
    stats["meshletsSkipped"] = {{"shadowOutside", frame.shadowMeshletsOutside},
                                {"viewOutside", frame.viewMeshletsOutside},
                                {"viewFacingAway", frame.viewMeshletsFacingAway}};
    stats["tiles"] = {{"rendered", frame.tilesRendered}, {"reused", frame.tilesReused}};
    stats["lightsPerCluster"] = {{"mean", frame.lightsPerClusterMean}, {"max", frame.lightsPerClusterMax}};
    const VirtualPageCounts& pages = frame.virtualPages;
    stats["virtualPages"] = {{"maps", pages.maps},           {"requested", pages.requested}, {"cached", pages.cached},
                             {"allocated", pages.allocated}, {"drawn", pages.drawn},         {"evicted", pages.evicted},
                             {"overflowed", pages.overflowed}, {"deferred", pages.deferred},
                             {"resident", pages.resident},     {"poolPages", pages.poolPages},
                             {"pagesPerFrame", pages.pagesPerFrame},
                             {"settled", pages.settled}};
    nlohmann::json maps = nlohmann::json::array();
    for (uint32_t map = 0; map < std::min<uint32_t>(pages.maps, uint32_t(frame.virtualMaps.size())); ++map) {
        const FrameStats::VirtualMapLevels& levels = frame.virtualMaps[map];
        nlohmann::json perLevel = nlohmann::json::array();
        for (uint32_t level = 0; level < levels.levelCount; ++level)
            perLevel.push_back({{"requested", levels.requested[level]}, {"cached", levels.cached[level]},
                                {"drawn", levels.drawn[level]}});
        maps.push_back({{"levels", perLevel}});
    }
    stats["virtualPages"]["perMap"] = maps;
    const VirtualPageCounts& faces = frame.virtualFacePages;
    nlohmann::json perMip = nlohmann::json::array();
    for (uint32_t mip = 0; mip < frame.virtualFaceMips.levelCount; ++mip)
        perMip.push_back({{"requested", frame.virtualFaceMips.requested[mip]}, {"cached", frame.virtualFaceMips.cached[mip]},
                          {"drawn", frame.virtualFaceMips.drawn[mip]}});
    stats["virtualFacePages"] = {{"faces", faces.maps},         {"requested", faces.requested}, {"cached", faces.cached},
                                 {"allocated", faces.allocated}, {"drawn", faces.drawn},         {"evicted", faces.evicted},
                                 {"overflowed", faces.overflowed}, {"deferred", faces.deferred},
                                 {"resident", faces.resident},     {"poolPages", faces.poolPages},
                                 {"pagesPerFrame", faces.pagesPerFrame},
                                 {"lodBiasSteps", faces.lodBiasSteps}, {"settled", faces.settled}, {"perMip", perMip}};
    return stats.dump();
}

}  // namespace penumbra
