// The tight cascade fit's depth reduction on the GPU (render/visible_surface_pass.h,
// visible_bounds.comp): the view's visible surfaces binned by view depth, log-spaced bins, each bin's
// bounds kept in a few rotated spaces (the frame's directional lights' and the world's), read back
// for the next frames' plans. shadows/visible_surfaces.h reads the words and is the CPU reference.
#ifndef PENUMBRA_VISIBLE_BOUNDS_STRUCTS_H
#define PENUMBRA_VISIBLE_BOUNDS_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kVisibleDepthBins, 1024u)
PENUMBRA_CONST(uint, kVisibleBoundsSpaces, 5u)  // the directional lights (at most 4) and the world
// The words: [0] the smallest view depth's key, then per space and bin the bounds' minimum x, y, z keys;
// from kVisibleBoundsMinWords the same for the maxima (the largest view depth, then the bounds'
// maximum keys). A key orders as its float does (visibleBoundsKey), so atomicMin and atomicMax on keys
// are min and max on floats; the minima start at 0xffffffff, the maxima at 0 (no surface).
PENUMBRA_CONST(uint, kVisibleBoundsMinWords, 1u + kVisibleBoundsSpaces * kVisibleDepthBins * 3u)
PENUMBRA_CONST(uint, kVisibleBoundsWords, 2u * kVisibleBoundsMinWords)

struct VisibleBoundsData {
    mat4 worldFromClip;                          // inverse of the camera's clipFromWorld
    mat4 spaceFromWorld[kVisibleBoundsSpaces];   // rotations (lightRotationFromWorld; identity = world)
    vec4 vsDepthRow;        // the view depth of a world point: dot(vsDepthRow, vec4(wsPoint, 1))
    uint width;             // the depth texture's size
    uint height;
    uint spaceCount;        // spaceFromWorld in use
    float vsBinNear;        // bin b starts at view depth vsBinNear * exp(b / binsPerLogDepth)
    float binsPerLogDepth;  // kVisibleDepthBins / log(vsBinFar / vsBinNear)
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(VisibleBoundsData, 432)
PENUMBRA_CHECK_LAYOUT(VisibleBoundsData, vsDepthRow, 384)
PENUMBRA_CHECK_LAYOUT(VisibleBoundsData, width, 400)
PENUMBRA_CHECK_LAYOUT(VisibleBoundsData, binsPerLogDepth, 416)

// The bin of a view depth: the first bin takes everything nearer, the last everything farther.
PENUMBRA_INLINE uint visibleDepthBin(float vsDepth, float vsBinNear, float binsPerLogDepth) {
    const float ratio = vsDepth > vsBinNear ? vsDepth / vsBinNear : 1.0f;
    const float bin = log(ratio) * binsPerLogDepth;  // >= 0 but for log's rounding just above a ratio of 1
    return bin < float(kVisibleDepthBins - 1u) ? (bin > 0.0f ? uint(bin) : 0u) : kVisibleDepthBins - 1u;
}

PENUMBRA_GPU_NAMESPACE_END
#endif
