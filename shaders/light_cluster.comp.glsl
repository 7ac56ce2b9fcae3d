#version 460
// Clustered light culling (issue 11 item 1): one invocation per cluster writes its light mask words
// (light_cluster_structs.h) and adds its light count to the frame's stats.
#include "scene_structs.h"
#include "lighting.glsl"
#include "light_clusters.glsl"

layout(local_size_x = kClusterWorkgroupSize) in;

layout(set = 0, binding = 4, std430) readonly buffer LightBlock { LightData lights[]; };
layout(set = 0, binding = kBindingClusterMasks, std430) writeonly buffer ClusterMaskBlock { uint clusterMasks[]; };
layout(set = 0, binding = kBindingClusterStats, std430) buffer ClusterStatsBlock { LightClusterStats clusterStats; };

void main() {
    uint cluster = gl_GlobalInvocationID.x;
    if (cluster >= kClusterCount) return;
    uvec3 coords = uvec3(cluster % kClusterTilesX, (cluster / kClusterTilesX) % kClusterTilesY,
                         cluster / (kClusterTilesX * kClusterTilesY));
    vec3 vsMin, vsMax;
    clusterViewBox(coords, vsMin, vsMax);
    uint words = clusters.config.z, count = 0u;
    for (uint word = 0u; word < words; ++word) {
        uint bits = 0u;
        for (uint bit = 0u; bit < 32u; ++bit) {
            uint light = word * 32u + bit;
            if (light < clusters.config.x && clusterLightTouchesBox(lights[clusters.config.y + light], vsMin, vsMax))
                bits |= 1u << bit;
        }
        clusterMasks[cluster * words + word] = bits;
        count += bitCount(bits);
    }
    atomicAdd(clusterStats.counts.x, count);
    atomicMax(clusterStats.counts.y, count);
}
