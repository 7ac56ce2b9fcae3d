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
                      {"record", frame.cpu.record}, {"submit", frame.cpu.submit}};
    stats["shadows"] = nlohmann::json::parse(toJson(frame.shadows));
    stats["warnings"] = frame.warnings;
    stats["shadowRaster"] = {{"used", frame.shadowRaster}, {"choice", frame.shadowRasterChoice}};
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
                             {"overflowed", pages.overflowed}, {"resident", pages.resident}, {"poolPages", pages.poolPages}};
    return stats.dump();
}

}  // namespace penumbra
