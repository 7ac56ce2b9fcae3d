// Clustered light culling (light_cluster_structs.h): the froxels' view-space
// boxes and the conservative light test, operation for operation as render/light_clusters.cpp
// (the reference the tests compare with), and the lit pass's lookup of a fragment's cluster.
#ifndef PENUMBRA_LIGHT_CLUSTERS_GLSL
#define PENUMBRA_LIGHT_CLUSTERS_GLSL
#include "pass_bindings.h"
#include "light_cluster_structs.h"

layout(set = kPassSet, binding = kLitBindingLightClusters, std140) uniform LightClusterBlock { LightClusterData clusters; };

// light_clusters.cpp viewPointAtDepth
vec3 clusterViewPointAtDepth(float ndcX, float ndcY, float vsDepth) {
    vec4 p = clusters.viewFromClip * vec4(ndcX, ndcY, 0.5, 1.0);
    vec3 onRay = p.xyz / p.w;
    return onRay * (vsDepth / -onRay.z);
}

float clusterSliceDepth(uint slice) { return clusters.nearDepth * exp(float(slice) / clusters.slicesPerLogDepth); }

// light_clusters.cpp clusterViewBox: the box around cluster (tile.x, tile.y, slice), grown.
void clusterViewBox(uvec3 cluster, out vec3 vsMin, out vec3 vsMax) {
    float x0 = 2.0 * float(cluster.x) / float(kClusterTilesX) - 1.0, x1 = 2.0 * float(cluster.x + 1u) / float(kClusterTilesX) - 1.0;
    float y0 = 2.0 * float(cluster.y) / float(kClusterTilesY) - 1.0, y1 = 2.0 * float(cluster.y + 1u) / float(kClusterTilesY) - 1.0;
    float d0 = clusterSliceDepth(cluster.z) * (1.0 - kClusterBoundsMargin);
    float d1 = clusterSliceDepth(cluster.z + 1u) * (1.0 + kClusterBoundsMargin);
    vsMin = vec3(uintBitsToFloat(0x7f800000u));
    vsMax = -vsMin;
    for (int corner = 0; corner < 8; ++corner) {
        vec3 p = clusterViewPointAtDepth((corner & 1) != 0 ? x1 : x0, (corner & 2) != 0 ? y1 : y0, (corner & 4) != 0 ? d1 : d0);
        vsMin = min(vsMin, p);
        vsMax = max(vsMax, p);
    }
    vec3 grow = kClusterBoundsMargin * max(abs(vsMin), abs(vsMax));
    vsMin -= grow;
    vsMax += grow;
}

// light_clusters.cpp lightTouchesViewBox: false only when the light adds nothing inside the box.
bool clusterLightTouchesBox(LightData light, vec3 vsMin, vec3 vsMax) {
    vec3 vsLight = (clusters.viewFromWorld * vec4(light.wsPosition.xyz, 1.0)).xyz;
    float inverseRangeSquared = light.invRangeSquared;
    bool ranged = inverseRangeSquared > 0.0;
    float range = ranged ? (1.0 + kClusterBoundsMargin) / sqrt(inverseRangeSquared) : 0.0;
    if (ranged) {
        vec3 offset = clamp(vsLight, vsMin, vsMax) - vsLight;
        if (dot(offset, offset) > range * range) return false;
    }
    if (light.type != kLightSpot) return true;
    vec3 vsAxis = normalize(mat3(clusters.viewFromWorld) * -light.wsToLight.xyz);
    float cosOuter = clamp(-light.spotOffset / light.spotScale, -1.0, 1.0);
    float angle = min(acos(cosOuter) * (1.0 + kClusterBoundsMargin) + kClusterBoundsMargin, kPi);
    vec3 center = 0.5 * (vsMin + vsMax);
    float radius = 0.5 * length(vsMax - vsMin);
    vec3 v = center - vsLight;
    float along = dot(v, vsAxis);
    float across = sqrt(max(dot(v, v) - along * along, 0.0));
    if (cos(angle) * across - along * sin(angle) > radius) return false;
    if (angle < 0.5 * kPi && along < -radius) return false;
    return !(ranged && along > radius + range);
}

// light_clusters.cpp clusterOfPixel: the cluster of a fragment, -1 beyond the last slice.
int clusterOfFragment(vec2 pixel, float vsDepth) {
    if (!(vsDepth <= clusters.farDepth)) return -1;
    float slice = floor(log(max(vsDepth, clusters.nearDepth) / clusters.nearDepth) * clusters.slicesPerLogDepth);
    uint z = min(uint(max(slice, 0.0)), kClusterSlices - 1u);
    uint x = min(uint(pixel.x * clusters.tilesPerPixel.x), kClusterTilesX - 1u);
    uint y = min(uint(pixel.y * clusters.tilesPerPixel.y), kClusterTilesY - 1u);
    return int((z * kClusterTilesY + y) * kClusterTilesX + x);
}
#endif
