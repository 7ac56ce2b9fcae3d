// GPU shadow-caster culling (issue 10), shared by C++ (render/shadow_culling_pass) and GLSL
// (shadow_cull.comp, shadow_draws.comp, shadow_caster.vert). One compute pass tests every instance
// against every shadow tile of the frame with the CPU planner's rules (shadows/caster_culling.h,
// shadows/spot_culling.h, which stay the reference the tests compare with) and appends the survivors
// to per-(tile, mesh) lists; a second pass turns the non-empty lists into compacted indirect draws,
// one list per tile and caster kind, drawn with vkCmdDrawIndexedIndirectCount.
//
// Visible-instance list layout: tile t, mesh m, entry i lives at
//   t * instanceCount + meshes[m].counts.x + i      (counts.x = the mesh's first slot, a prefix sum)
// so a draw's firstInstance is where its list starts and gl_InstanceIndex indexes the list.
#ifndef PENUMBRA_CULL_STRUCTS_H
#define PENUMBRA_CULL_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kMaxCullTiles, 32u)  // 16 directional (4 lights x 4 cascades) + 16 spot/point
PENUMBRA_CONST(uint, kCullWorkgroupSize, 64u)
PENUMBRA_CONST(uint, kCasterKinds, 2u)  // 0: opaque (depth-only pipeline), 1: alpha-tested (clip, dither)
PENUMBRA_CONST(uint, kCullInstanceCasts, 1u)  // CullInstance.info.y bit: node casts and has bounds
PENUMBRA_CONST(uint, kCullInstanceBounded, 2u)  // CullInstance.info.y bit: wsMin / wsMax hold its bounds
PENUMBRA_CONST(uint, kCullTileDirectional, 0u)
PENUMBRA_CONST(uint, kCullTilePerspective, 1u)

// Per instance; rewritten when its transform or cast flag changes.
struct CullInstance {
    vec4 wsMin;   // xyz: world bounds
    vec4 wsMax;
    uvec4 info;   // x = mesh slot (index into CullMesh; 0 without geometry), y = kCullInstance* bits
};
PENUMBRA_CHECK_SIZE(CullInstance, 48)

// Per mesh with geometry.
struct CullMesh {
    uvec4 draw;    // x = index count, y = first index, z = vertex offset (int bits), w = material index
    uvec4 counts;  // x = first slot of the mesh's instances in a tile's list, y = its instance count,
                   // z = its first compute-raster work item, w = triangle batches per instance
};
PENUMBRA_CHECK_SIZE(CullMesh, 32)

// Per shadow tile of the frame (both atlases, directional first).
struct CullTile {
    mat4 lightFromWorld;  // directional: the cascade's light view (rotation + translation)
    vec4 planes[5];       // perspective: clip-frustum planes (shadows/spot_culling.h)
    vec4 frustumMin;      // perspective: world bounds of the frustum; w = kind (kCullTile*)
    vec4 frustumMax;
    vec4 params;          // directional: x = half extent, y = far distance, z = cascade index, w = blend culling factor
    vec4 wsLightDirection;  // directional: xyz = the way the light travels; w = slope-scale depth bias
    // The compute rasterizer (shadow_raster.glsl): what the caster pass's vertex shader and viewport do.
    mat4 clipFromWorld;
    vec4 viewport;        // x, y, width, height in atlas texels
    uvec4 scissor;        // x0, y0, x1, y1 (exclusive) in atlas texels
};
PENUMBRA_CHECK_SIZE(CullTile, 304)
PENUMBRA_CHECK_LAYOUT(CullTile, planes, 64)
PENUMBRA_CHECK_LAYOUT(CullTile, frustumMin, 144)
PENUMBRA_CHECK_LAYOUT(CullTile, params, 176)
PENUMBRA_CHECK_LAYOUT(CullTile, clipFromWorld, 208)
PENUMBRA_CHECK_LAYOUT(CullTile, viewport, 272)

struct CullFrame {
    CullTile tiles[32];
    vec4 spheres[4];           // cascade culling spheres: xyz centre, w radius (shared by every light)
    vec4 wsReceiverMin;        // bounds of every shadow receiver (blend culling's reach of shadows)
    vec4 wsReceiverMax;
    uvec4 counts;              // x = tiles, y = instances, z = meshes
    // The tiles the compute rasterizer draws this frame (the others are cached), 4 per uvec4: the
    // directional atlas's first, then the spot/point atlas's; a raster pass reads its part.
    uvec4 rasterTiles[8];
};
PENUMBRA_CHECK_SIZE(CullFrame, 9968)
PENUMBRA_CHECK_LAYOUT(CullFrame, spheres, 9728)
PENUMBRA_CHECK_LAYOUT(CullFrame, counts, 9824)
PENUMBRA_CHECK_LAYOUT(CullFrame, rasterTiles, 9840)

// What one tile drew, accumulated by shadow_draws.comp and read back when the frame is done.
struct CullTileStats {
    uvec4 counts;  // x = draws (indirect commands), y = instances drawn, z = triangles, w unused
};
PENUMBRA_CHECK_SIZE(CullTileStats, 16)

// ---- compute rasterizer of shadow depth (shadow_raster.glsl)
// Triangle pieces whose clamped bounding box covers more than kRasterSmallArea texels are not
// rasterized by the thread that set them up but queued (already set up), split into kRasterChunk x
// kRasterChunk chunks, and rasterized one workgroup per chunk, kRasterChunk^2 / 256 texels a thread.
PENUMBRA_CONST(uint, kRasterSmallArea, 64u)
PENUMBRA_CONST(uint, kRasterChunk, 16u)
// Pass 1 works in batches of kRasterBatch triangles of one instance (one workgroup each), so a mesh
// of many triangles on few instances still fills the GPU.
PENUMBRA_CONST(uint, kRasterBatch, 128u)
// The queues of large pieces and chunks start at these capacities and grow when a frame overflows
// them (the renderer reads the counters back; render() draws the frame again).
PENUMBRA_CONST(uint, kRasterInitialLarge, 262144u)
PENUMBRA_CONST(uint, kRasterInitialChunks, 1048576u)
PENUMBRA_CONST(uint, kRasterDispatchWidth, 65535u)

// A queued large piece, set up (shadow_raster.glsl RasterTriangleSetup, packed).
struct RasterPiece {
    ivec4 points01;     // snapped window positions of vertices 0 and 1 (1/256 texel)
    ivec4 point2;       // xy = vertex 2, z = material index, w = 1 alpha-tested
    vec4 depth;         // xyz = window z per vertex, w = twice the area in sub-texel units
    vec4 inverseW;      // xyz = 1 / w per vertex, w = the tile's slope-scale bias
    vec4 uvOverW01;
    vec4 uvOverW2Slope; // xy = uv / w of vertex 2, zw = dz per texel in x, y
    ivec4 bounds;       // texels x0, y0, x1, y1 inclusive
};
PENUMBRA_CHECK_SIZE(RasterPiece, 112)

// Counters of one atlas pass: x = large triangles queued, y = chunks queued, z = large triangles
// dropped (queue full), w = chunks dropped; then the two indirect dispatches (x, y, z) sized from them.
struct RasterCounters {
    uvec4 counts;
    uvec4 largeDispatch;
    uvec4 chunkDispatch;
};
PENUMBRA_CHECK_SIZE(RasterCounters, 48)

PENUMBRA_GPU_NAMESPACE_END
#endif
