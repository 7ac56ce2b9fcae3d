// The shadow lookup into a directional light's virtual shadow map, shared by C++ (shadows/
// virtual_shadow_lookup.h, the CPU reference) and GLSL (penumbra/shadows/virtual_shadow_lookup.glsl, and the tests'
// virtual_shadow_probe.comp): what the lookup needs of the clipmap, the light and the pool.
//
// Spaces and units (virtual_page_draw_structs.h has the drawing side): light space is the light's
// rotation (clipmapRotationFromWorld, the light travels along -z); a level's virtual texel (x, y) covers
// light-space [x, x + 1) * lsTexelSize by [y, y + 1) * lsTexelSize, lsTexelSize = firstLevelSize * 2^level
// / resolution; page (px, py) holds texels px * pageSize .. px * pageSize + pageSize - 1 (and so for y);
// depth is light-space z mapped linearly from lsDepthNear (0) to lsDepthFar (1).
#ifndef PENUMBRA_VIRTUAL_SHADOW_STRUCTS_H
#define PENUMBRA_VIRTUAL_SHADOW_STRUCTS_H
#include "gpu_shared.h"
#include "virtual_page_structs.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(int, kVirtualShadowNoLevel, -1)  // VirtualShadowProbeResult::level: no level held the receiver (lit)
PENUMBRA_CONST(uint, kVirtualShadowProbeGroup, 64u)  // local_size_x of virtual_shadow_probe.comp

// The clipmap as the lookup reads it (a uniform buffer): the light, the depth mapping, the clipmap's
// configuration and each level's window this frame (VirtualPageTableData's windows).
struct VirtualShadowLookupData {
    mat4 lightRotationFromWorld;  // the clipmap's space
    float lsDepthNear;            // light-space z of depth 0
    float depthPerMetre;          // 1 / (lsDepthNear - lsDepthFar): depth = (lsDepthNear - z) * depthPerMetre
    float firstLevelSize;         // metres along level 0's side
    uint resolution;              // virtual texels along a level's side
    uint pagesPerSide;            // resolution / pageSize
    uint pageSize;                // texels along a page's side
    uint levelCount;
    uint poolPagesPerSide;        // physical page p lies at (p % poolPagesPerSide, p / poolPagesPerSide) * pageSize
    float texelsPerMetre;         // level 0's virtual texels per light-space metre: resolution / firstLevelSize
    uint poolOriginY;             // pool texture texels: this map's pool starts at row poolOriginY, column 0
    uint firstEntry;              // this map's entry e is record firstEntry + e of the bound entry buffer
    // 0: a clipmap (levels[] are its windows). Else the faces of spot and point lights (shadows/virtual_faces.h):
    // a table of fixed windows, level = mip * faceCount + face, the next coarser mip faceCount levels on;
    // lightRotationFromWorld, the depth fields, firstLevelSize, texelsPerMetre and levels[] unused.
    uint faceCount;
    VirtualPageLevelWindow levels[kVirtualPageMaxLevels];
};
PENUMBRA_CHECK_SIZE(VirtualShadowLookupData, 112 + 16 * 16)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, lsDepthNear, 64)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, pagesPerSide, 80)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, texelsPerMetre, 96)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, poolOriginY, 100)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, firstEntry, 104)
PENUMBRA_CHECK_LAYOUT(VirtualShadowLookupData, levels, 112)

// A point virtual_shadow_probe.comp evaluates: a receiver (its biases applied) and its pixel footprint.
struct VirtualShadowProbePoint {
    vec3 wsPosition;
    float wsFootprint;  // metres
};
PENUMBRA_CHECK_SIZE(VirtualShadowProbePoint, 16)

// What the probe found there.
struct VirtualShadowProbeResult {
    float lit;  // the 2 x 2 bilinear-weighted compare: 1 lit, 0 shadowed
    int level;  // the level that served the lookup, or kVirtualShadowNoLevel
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(VirtualShadowProbeResult, 16)

// Push constants of virtual_shadow_probe.comp.
struct VirtualShadowProbeConstants {
    uint pointCount;
    uint entryCount;  // VirtualPageEntry records bound (at least the lookup's firstEntry + levelCount * pagesPerSide^2)
    uint firstFace;   // virtual_face_probe.comp: the light's first face
    uint point;       // and 1 when it has six (a point light)
};
PENUMBRA_CHECK_SIZE(VirtualShadowProbeConstants, 16)

PENUMBRA_GPU_NAMESPACE_END
#endif
