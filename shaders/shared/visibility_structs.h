// The visibility-buffer main view, shared by C++ (render/visibility_pass) and GLSL
// (visibility_raster*.comp, visibility_resolve.comp).
//
// Opaque and alpha-tested triangles are rasterized in compute into one 64-bit word per pixel:
//   (floatBitsToUint(reversed-Z depth) << 32) | payload,    payload = ((instance << triangleBits) | triangle) + 1
// by atomicMax (reversed Z: the nearest surface has the largest depth; depth >= 0 orders like its
// bits). 0 = nothing drawn. The resolve reads the word back, rebuilds the surface from the triangle
// (perspective-correct barycentrics, analytic uv gradients) and shades it with shade_surface.glsl.
#ifndef PENUMBRA_VISIBILITY_STRUCTS_H
#define PENUMBRA_VISIBILITY_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kResolveGroupSize, 8u)           // the resolve's 8 x 8 workgroups

// Push constants of every visibility pass (the rasterizer's and the resolve's).
struct VisibilityConstants {
    uint width;           // of the view
    uint height;
    uint triangleBits;    // of the payload
    uint encodeSrgb;      // 1: the colour target wants sRGB-encoded values
    uint largeCapacity;   // large pieces the queue holds
    uint chunkCapacity;   // chunks the queue holds
    uint background;      // colour (RGBA8) where nothing was drawn
    uint meshSlots;
    // The rasterizer's: the culling list it draws (kCullListCamera*), the instances of a list,
    // 1: skip meshlets outside the view or facing away (render.meshletCulling), the visible-instance
    // lists per buffer (cull_structs.h).
    uint list;
    uint instanceCount;
    uint meshletCulling;
    uint listsPerBuffer;
    // The resolve's: 1 where no surface is drawn shows the colour output's gradient background (render.
    // background, background.frag's), not the colour `background`.
    uint backgroundGradient;
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(VisibilityConstants, 64)
PENUMBRA_CHECK_LAYOUT(VisibilityConstants, largeCapacity, 16)
PENUMBRA_CHECK_LAYOUT(VisibilityConstants, list, 32)

// The depth pyramid of the main view's occlusion culling (cull_structs.h CullCamera), built by
// depth_pyramid.comp one level a dispatch: level 0 from the visibility buffer, the others from the
// level below.
PENUMBRA_CONST(uint, kPyramidGroupSize, 8u)
struct PyramidConstants {
    uint sourceOffset;  // first texel of the level read
    uint sourceWidth;
    uint sourceHeight;
    uint fromVisibility;  // 1: the level read is the visibility buffer
    uint targetOffset;  // first texel of the level written
    uint targetWidth;
    uint targetHeight;
};
PENUMBRA_CHECK_SIZE(PyramidConstants, 28)

PENUMBRA_GPU_NAMESPACE_END
#endif
