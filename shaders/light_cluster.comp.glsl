#version 460
// Clustered light culling: one workgroup per cluster, one invocation per mask word
// (32 lights), writes the cluster's light mask (light_cluster_structs.h) and adds its light count
// to the frame's stats.
#include "pass_bindings.h"
#include "scene_structs.h"
#include "lighting.glsl"
#include "light_clusters.glsl"

layout(local_size_x = kMaxClusterLightWords) in;

layout(set = kPassSet, binding = kSceneBindingLights, std430) readonly buffer LightBlock { LightData lights[]; };
layout(set = kPassSet, binding = kLitBindingClusterMasks, std430) writeonly buffer ClusterMaskBlock { uint clusterMasks[]; };
layout(set = kPassSet, binding = kClusterBindingStats, std430) buffer ClusterStatsBlock { LightClusterStats clusterStats; };

shared uint clusterLightCount;

void main() {
    uint cluster = gl_WorkGroupID.x, word = gl_LocalInvocationID.x, words = clusters.wordsPerCluster;
    if (word == 0u) clusterLightCount = 0u;
    barrier();
    if (word < words) {
        uvec3 coords = uvec3(cluster % kClusterTilesX, (cluster / kClusterTilesX) % kClusterTilesY,
                             cluster / (kClusterTilesX * kClusterTilesY));
        vec3 vsMin, vsMax;
        clusterViewBox(coords, vsMin, vsMax);
        uint bits = 0u;
        for (uint bit = 0u; bit < 32u; ++bit) {
            uint light = word * 32u + bit;
            if (light < clusters.lightCount && clusterLightTouchesBox(lights[clusters.firstLight + light], vsMin, vsMax))
                bits |= 1u << bit;
        }
        clusterMasks[cluster * words + word] = bits;
        atomicAdd(clusterLightCount, uint(bitCount(bits)));
    }
    barrier();
    if (word == 0u) {
        atomicAdd(clusterStats.lightBits, clusterLightCount);
        atomicMax(clusterStats.mostLightsInACluster, clusterLightCount);
    }
}
