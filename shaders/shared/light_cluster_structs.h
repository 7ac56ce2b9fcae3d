// Clustered light culling (render.lightCulling), shared by C++ (render/light_clusters, the CPU reference,
// and render/light_cluster_pass) and GLSL (light_cluster.comp, light_clusters.glsl, lit.frag).
//
// The view is cut into froxels: kClusterTilesX x kClusterTilesY screen tiles times kClusterSlices
// depth slices, spaced exponentially in view depth from the camera's near plane to `farDepth` (the
// camera's far plane, or the far end of the scene's bounds when the camera's is infinite). Each
// cluster holds one bit per spot / point light: set when the light's range sphere (and, for a spot,
// its cone) touches the cluster's view-space bounding box. The test is conservative, so a light whose
// bit is clear adds exactly nothing to any pixel of the cluster: the clustered image equals the
// unculled one. Pixels beyond the last slice (possible only when the scene moved outside its
// bounds) loop over every light. Directional lights are never culled.
//
// Mask layout: cluster c = (slice * kClusterTilesY + tileY) * kClusterTilesX + tileX, word w of
// wordsPerCluster lives at c * wordsPerCluster + w; bit b of word w is spot / point light w * 32 + b,
// i.e. LightData index firstLight + w * 32 + b.
#ifndef PENUMBRA_LIGHT_CLUSTER_STRUCTS_H
#define PENUMBRA_LIGHT_CLUSTER_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kClusterTilesX, 16u)
PENUMBRA_CONST(uint, kClusterTilesY, 9u)
PENUMBRA_CONST(uint, kClusterSlices, 24u)
PENUMBRA_CONST(uint, kClusterCount, 3456u)  // 16 x 9 x 24
PENUMBRA_CONST(uint, kMaxClusterLightWords, 32u)  // 32 x 32 = 1024 spot / point lights (kMaxOtherLights)
// Relative growth of every light's range and of its cone's sine before the tests, so that the
// shader's float rounding in world space can never light a pixel the view-space test left out.
PENUMBRA_CONST(float, kClusterBoundsMargin, 1.0e-3f)

struct LightClusterData {
    mat4 viewFromClip;   // inverse projection: froxel corners from NDC
    mat4 viewFromWorld;  // lights into view space
    float nearDepth;         // view depth of the first slice's near end
    float farDepth;          // view depth of the last slice's far end
    float slicesPerLogDepth; // kClusterSlices / log(far / near)
    float reserved;
    vec2 tilesPerPixel;      // kClusterTilesX / width, kClusterTilesY / height
    vec2 viewSize;           // width, height in pixels
    uint lightCount;         // spot / point lights
    uint firstLight;         // LightData index of the first spot / point light
    uint wordsPerCluster;    // mask words per cluster
    uint clustered;          // 1 clustered (0: every pixel loops over every light)
};
PENUMBRA_CHECK_SIZE(LightClusterData, 176)
PENUMBRA_CHECK_LAYOUT(LightClusterData, nearDepth, 128)
PENUMBRA_CHECK_LAYOUT(LightClusterData, tilesPerPixel, 144)
PENUMBRA_CHECK_LAYOUT(LightClusterData, viewSize, 152)
PENUMBRA_CHECK_LAYOUT(LightClusterData, lightCount, 160)

// What the cluster pass counts for --stats.
struct LightClusterStats {
    uint lightBits;               // light bits set over all clusters
    uint mostLightsInACluster;
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(LightClusterStats, 16)

PENUMBRA_GPU_NAMESPACE_END

#endif
