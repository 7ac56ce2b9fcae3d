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

// Set 0 bindings of the visibility rasterizer beyond raster_mesh.glsl's 6, 7, 9-11.
PENUMBRA_CONST(uint, kBindingVisibility, 8u)          // uint64 per pixel
PENUMBRA_CONST(uint, kBindingViewListCounts, 12u)     // the culling pass's list counts (cull_structs.h)
PENUMBRA_CONST(uint, kBindingViewLists, 13u)          // and lists: the main view's are kCullListCamera*
// Set 0 bindings of the resolve beyond the shaded scene's 0-15.
PENUMBRA_CONST(uint, kBindingResolveVisibility, 16u)
PENUMBRA_CONST(uint, kBindingResolveIndices, 17u)
PENUMBRA_CONST(uint, kBindingResolveMeshes, 18u)      // CullMesh
PENUMBRA_CONST(uint, kBindingResolveInstances, 19u)   // CullInstance (its mesh slot)
PENUMBRA_CONST(uint, kBindingResolvedColor, 20u)      // RGBA8 per pixel, copied into the colour target
PENUMBRA_CONST(uint, kBindingResolvedDepth, 21u)      // float per pixel, copied into the depth target
PENUMBRA_CONST(uint, kResolveGroupSize, 8u)           // the resolve's 8 x 8 workgroups

// Push constants of every visibility pass (the rasterizer's RasterConstants block has this shape).
struct VisibilityConstants {
    uvec4 view;      // x = width, y = height, z = triangle bits of the payload, w = 1: encode sRGB
    uvec4 capacity;  // x = large pieces, y = chunks the queues hold; z = background colour (RGBA8); w = mesh slots
    uvec4 list;      // the rasterizer: x = the culling list it draws (kCullListCamera*), y = instances,
                     // z = 1: skip meshlets outside the view or facing away (render.meshletCulling)
};
PENUMBRA_CHECK_SIZE(VisibilityConstants, 48)
PENUMBRA_CHECK_LAYOUT(VisibilityConstants, capacity, 16)

// The depth pyramid of the main view's occlusion culling (cull_structs.h CullCamera), built by
// depth_pyramid.comp one level a dispatch: level 0 from the visibility buffer, the others from the
// level below.
PENUMBRA_CONST(uint, kBindingPyramidVisibility, 0u)
PENUMBRA_CONST(uint, kBindingPyramid, 1u)
PENUMBRA_CONST(uint, kPyramidGroupSize, 8u)
struct PyramidConstants {
    uvec4 source;  // x = first texel of the level read, y = width, z = height, w = 1: the visibility buffer
    uvec4 target;  // x = first texel of the level written, y = width, z = height
};
PENUMBRA_CHECK_SIZE(PyramidConstants, 32)

PENUMBRA_GPU_NAMESPACE_END
#endif
