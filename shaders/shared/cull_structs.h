// GPU shadow-caster culling, shared by C++ (render/shadow_culling_pass) and GLSL
// (shadow_cull.comp, shadow_draws.comp, shadow_caster.vert). One compute pass tests every instance
// against every shadow tile of the frame with the CPU planner's rules (shadows/caster_culling.h,
// shadows/spot_culling.h, which stay the reference the tests compare with) and appends the survivors
// to per-(tile, mesh) lists; a second pass turns the non-empty lists into compacted indirect draws,
// one list per tile and caster kind, drawn with vkCmdDrawIndexedIndirectCount.
//
// Visible-instance list layout: every list (a tile's, or the main view's) has room for every instance:
// tile t, mesh m, entry i lives at
//   visibleListStart(t) + meshes[m].firstListSlot + i    (a prefix sum over the meshes' instance counts)
// of buffer visibleListBuffer(t): the lists are split over up to kVisibleListBuffers storage buffers of
// listsPerBuffer lists each (render/gpu_scene.h splitVisibleLists), so that no binding is larger than the
// device's maxStorageBufferRange (34 lists of 10^6 instances are 130 MiB, over the 128 MiB that Vulkan
// guarantees). A draw's firstInstance is where its list starts in its buffer, and gl_InstanceIndex
// indexes that buffer (the caster pass binds each tile's buffer).
//
// The main view's visibility buffer (render.mainView = visibility) is culled by the same pass, in two more
// lists after the shadow tiles' (kCullListCameraEarly, kCullListCameraLate), by two-phase occlusion culling:
// the early list holds the instances inside the camera frustum that were visible last frame; they are
// rasterized, a depth pyramid is built from the visibility buffer (CullCamera), and the late pass tests every
// instance in the frustum against it: those not hidden are this frame's visible set (kept per instance for
// the next frame), and the ones of them the early list lacked are the late list, rasterized on top. Nothing
// visible is missed, whatever last frame's set was.
#ifndef PENUMBRA_CULL_STRUCTS_H
#define PENUMBRA_CULL_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// The atlases' tiles a frame: 16 directional (4 lights x 4 cascades) + 16 spot/point. A culling pass
// made for more (the virtual pages') has as many tile lists and records no main view.
PENUMBRA_CONST(uint, kMaxCullTiles, 32u)
PENUMBRA_CONST(uint, kCullListCameraEarly, 32u)  // kMaxCullTiles: the main view's lists follow the tiles'
PENUMBRA_CONST(uint, kCullListCameraLate, 33u)
PENUMBRA_CONST(uint, kCullListCount, 34u)
PENUMBRA_CONST(uint, kCullWorkgroupSize, 64u)
PENUMBRA_CONST(uint, kCasterKinds, 2u)  // 0: opaque (depth-only pipeline), 1: alpha-tested (clip, dither)
PENUMBRA_CONST(uint, kCullInstanceCasts, 1u)  // CullInstance.flags bit: node casts and has bounds
PENUMBRA_CONST(uint, kCullInstanceBounded, 2u)  // CullInstance.flags bit: wsMin / wsMax hold its bounds
PENUMBRA_CONST(uint, kCullInstanceHasMesh, 4u)  // CullInstance.flags bit: the instance has geometry (a mesh slot)
// What a culling dispatch does (CullConstants.pass): the shadow tiles, or a main-view phase.
PENUMBRA_CONST(uint, kCullPassShadows, 0u)
PENUMBRA_CONST(uint, kCullPassCameraEarly, 1u)
PENUMBRA_CONST(uint, kCullPassCameraLate, 2u)
// How the main view culls (CullCamera.culling, render.viewCulling).
PENUMBRA_CONST(uint, kViewCullingNone, 0u)
PENUMBRA_CONST(uint, kViewCullingFrustum, 1u)
PENUMBRA_CONST(uint, kViewCullingOcclusion, 2u)
// Per-instance main-view history word (ShadowCullingPass::viewHistory): bit 0 = visible in the last
// finished late pass, bit 1 = drawn by this frame's early list.
PENUMBRA_CONST(uint, kViewVisible, 1u)
PENUMBRA_CONST(uint, kViewDrawnEarly, 2u)
PENUMBRA_CONST(uint, kMaxPyramidLevels, 16u)
PENUMBRA_CONST(uint, kCullTileDirectional, 0u)
PENUMBRA_CONST(uint, kCullTilePerspective, 1u)
PENUMBRA_CONST(uint, kVisibleListBuffers, 4u)  // the most storage buffers the visible lists are split over

// Which buffer of the visible-instance lists holds list `list`, and where in it the list starts.
PENUMBRA_INLINE uint visibleListBuffer(uint list, uint listsPerBuffer) { return list / listsPerBuffer; }
PENUMBRA_INLINE uint visibleListStart(uint list, uint listsPerBuffer, uint instanceCount) {
    return (list % listsPerBuffer) * instanceCount;
}

// Per instance; rewritten when its transform or cast flag changes.
struct CullInstance {
    vec4 wsMin;   // xyz: world bounds
    vec4 wsMax;
    uint meshSlot;  // index into CullMesh; 0 without geometry
    uint flags;     // kCullInstance* bits
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(CullInstance, 48)
PENUMBRA_CHECK_LAYOUT(CullInstance, meshSlot, 32)

// Per mesh with geometry.
struct CullMesh {
    uint indexCount;
    uint firstIndex;
    int vertexOffset;
    uint materialIndex;
    uint firstListSlot;    // of the mesh's instances in a tile's list
    uint instanceCount;
    uint firstRasterItem;  // its first compute-raster work item
    uint meshletCount;     // its meshlets (work items per instance)
    uint firstMeshlet;
    uint packedInstances;  // > 1: a one-meshlet mesh whose instances the rasterizers take this many to a work item
    uint lodCount;         // its simplified levels for the shadow rasterizer (scene/meshlets.h), <= kMaxShadowLods
    uint reserved2;
    uvec4 lodFirstMeshlet; // level i + 1's first meshlet, in the scene's meshlets (as firstMeshlet)
    uvec4 lodMeshletCount;
    vec4 lodError;         // level i + 1's object-space error: how far its surface may lie from the full mesh's
    vec4 osSphere;         // xyz: centre of the mesh's bounds, w: their half diagonal
};
PENUMBRA_CHECK_SIZE(CullMesh, 112)
PENUMBRA_CHECK_LAYOUT(CullMesh, firstListSlot, 16)
PENUMBRA_CHECK_LAYOUT(CullMesh, firstMeshlet, 32)
PENUMBRA_CHECK_LAYOUT(CullMesh, lodFirstMeshlet, 48)
PENUMBRA_CONST(uint, kMaxShadowLods, 4u)

// The compute rasterizers' unit of work (scene/meshlets.h): up to kRasterBatch triangles of one mesh,
// near each other (meshoptimizer's meshlets), stored consecutively in the index buffer, with bounds
// that let a whole meshlet be skipped (shaders/meshlet_culling.glsl, render.meshletCulling): outside
// the view or tile, or, for the main view, every triangle facing away from the camera.
struct Meshlet {
    vec4 osMin;       // xyz: object-space bounds of its vertices; w unused
    vec4 osMax;
    vec4 coneApex;    // xyz: apex of its normal cone (meshopt_computeClusterBounds); w unused
    vec3 coneAxis;
    float coneCutoff; // >= 1: the normals spread too far for a cone
    uint firstTriangle;  // counted from the mesh's first index / 3
    uint triangleCount;
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(Meshlet, 80)
PENUMBRA_CHECK_LAYOUT(Meshlet, firstTriangle, 64)

// Per shadow tile of the frame (both atlases, directional first).
struct CullTile {
    mat4 lightFromWorld;  // directional: the cascade's light view (rotation + translation)
    vec4 planes[5];       // perspective: clip-frustum planes (shadows/spot_culling.h)
    vec3 frustumMin;      // perspective: world bounds of the frustum
    uint kind;            // kCullTile*
    vec3 frustumMax;
    float reserved0;
    // Directional: the cascade's half extent and far distance, its index, the blend culling factor.
    float halfExtent;
    float farDistance;
    float cascadeIndex;
    float blendCullingFactor;
    vec3 wsLightDirection;  // directional: the way the light travels
    float slopeBias;        // slope-scale depth bias
    // The compute rasterizer (shadow_raster.glsl): what the caster pass's vertex shader and viewport do.
    mat4 clipFromWorld;
    vec4 viewport;        // x, y, width, height in atlas texels
    uvec4 scissor;        // x0, y0, x1, y1 (exclusive) in atlas texels
    // Directional receiver culling (shadows/caster_culling.h ReceiverVolume): planes[0..3] the camera's
    // unit side planes, planes[4] its view depth (dot(xyz, p) + w); receiverDepth.xy the depth range,
    // .z the lookups' reach in world units, .w 1 when on; receiverSphere the culling sphere (w < 0: none).
    vec4 receiverDepth;
    vec4 receiverSphere;
};
PENUMBRA_CHECK_SIZE(CullTile, 336)
PENUMBRA_CHECK_LAYOUT(CullTile, planes, 64)
PENUMBRA_CHECK_LAYOUT(CullTile, frustumMin, 144)
PENUMBRA_CHECK_LAYOUT(CullTile, kind, 156)
PENUMBRA_CHECK_LAYOUT(CullTile, frustumMax, 160)
PENUMBRA_CHECK_LAYOUT(CullTile, halfExtent, 176)
PENUMBRA_CHECK_LAYOUT(CullTile, blendCullingFactor, 188)
PENUMBRA_CHECK_LAYOUT(CullTile, slopeBias, 204)
PENUMBRA_CHECK_LAYOUT(CullTile, clipFromWorld, 208)
PENUMBRA_CHECK_LAYOUT(CullTile, viewport, 272)
PENUMBRA_CHECK_LAYOUT(CullTile, receiverDepth, 304)

// The main view as its culling sees it. The depth pyramid (a float buffer, reversed Z) has `levels`
// levels, level 0 of (width + 1) / 2 x (height + 1) / 2 texels, each level half the previous one
// rounded up; a texel holds the farthest (smallest) depth of the 2 x 2 texels (level 0: pixels)
// under it, so texel (x, y) of level L covers pixels [x, x + 1) * 2^(L+1) in each axis.
struct CullCamera {
    mat4 clipFromWorld;
    uint width;
    uint height;
    uint pyramidLevels;
    uint culling;        // kViewCulling*
    uint pyramidWidth;   // of level 0
    uint pyramidHeight;
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(CullCamera, 96)
PENUMBRA_CHECK_LAYOUT(CullCamera, width, 64)
PENUMBRA_CHECK_LAYOUT(CullCamera, pyramidWidth, 80)

// What every culling dispatch reads besides its tiles (a uniform buffer).
struct CullFrame {
    vec4 spheres[4];           // cascade culling spheres: xyz centre, w radius (shared by every light)
    vec4 wsReceiverMin;        // bounds of every shadow receiver (blend culling's reach of shadows)
    vec4 wsReceiverMax;
    uint instanceCount;
    uint meshCount;
    uint reserved0;
    uint reserved1;
    CullCamera camera;
};
PENUMBRA_CHECK_SIZE(CullFrame, 208)
PENUMBRA_CHECK_LAYOUT(CullFrame, wsReceiverMin, 64)
PENUMBRA_CHECK_LAYOUT(CullFrame, instanceCount, 96)
PENUMBRA_CHECK_LAYOUT(CullFrame, camera, 112)

// ---- Tile lists (storage buffers, std430), written by the CPU (the atlases' tiles: shadows/cull_packing.h)
// or by the GPU (the virtual shadow map's dirty pages: render/virtual_page_draw_pass.h), so that the
// culling and raster passes read one layout and size their per-tile loops by the list's count through
// vkCmdDispatchIndirect, never by a CPU-known number. Both headers hold the dispatches of the passes that
// loop over their tiles.
//
// The culling list: this header, then `count` CullTile records (culling tile i = record i).
struct CullTileListHeader {
    uvec4 cullDispatch;   // shadow_cull.comp: (ceil(instances / kCullWorkgroupSize), count, 1)
    uvec4 drawsDispatch;  // shadow_draws.comp: (ceil(meshes / kCullWorkgroupSize), count, 1)
    uint count;           // tiles in the list
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(CullTileListHeader, 48)
PENUMBRA_CHECK_LAYOUT(CullTileListHeader, count, 32)

// The raster list of one compute-raster pass: this header, then `count` culling tile indices (the tiles
// it draws into its depth buffer, each at its CullTile's viewport). The clear and pass-1 dispatches
// loop over the entries in z.
PENUMBRA_CONST(uint, kRasterClearGroup, 16u)
PENUMBRA_CONST(uint, kRasterExpandGroup, 64u)  // shadow_raster_expand.comp's workgroup: slots of a tile's list  // shadow_raster_clear.comp's workgroup side, in texels
struct RasterTileListHeader {
    uvec4 clearDispatch;     // shadow_raster_clear.comp: (ceil(largest side / kRasterClearGroup) x 2, count)
    uvec4 expandDispatch;    // shadow_raster_expand.comp: (ceil(instances / kRasterExpandGroup), 1, count)
    uint count;              // entries in the list
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(RasterTileListHeader, 48)
PENUMBRA_CHECK_LAYOUT(RasterTileListHeader, count, 32)

// Push constants of the culling pass and of its draw lists (shadow_draws.comp).
struct CullConstants {
    uint pass;            // kCullPass*
    uint listsPerBuffer;  // of the visible-instance lists
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(CullConstants, 16)

// What one tile drew, accumulated by shadow_draws.comp and read back when the frame is done; the
// main view's two lists count instances and triangles in the culling pass itself.
struct CullTileStats {
    uint draws;  // indirect commands
    uint instances;
    uint triangles;
    uint reserved;
};
PENUMBRA_CHECK_SIZE(CullTileStats, 16)

// ---- compute rasterizer of shadow depth (shadow_raster.glsl)
// Large triangle pieces are not rasterized by the thread that set them up but queued (already set
// up), split into kRasterChunk x kRasterChunk chunks, and rasterized one workgroup per chunk,
// kRasterChunk^2 / 256 texels a thread. The visibility rasterizer queues those whose clamped bounding
// box covers more than kRasterSmallArea texels; the shadow rasterizer keeps pieces of up to 2048 for
// its workgroups (shadow_raster.glsl, kShadowMediumArea) and queues only larger ones.
PENUMBRA_CONST(uint, kRasterSmallArea, 64u)
PENUMBRA_CONST(uint, kRasterChunk, 16u)
// Pass 1 works in meshlets of at most kRasterBatch triangles of one instance, so a mesh of many
// triangles on few instances still fills the GPU. Before it, shadow_raster_expand.comp turns each
// (drawn tile, instance its culling kept) into work items of at most kRasterMeshletsPerItem meshlets
// (RasterWorkItem), one workgroup of pass 1 each: the dispatch holds only what a tile draws, however
// many tiles or pages a pass draws and however many instances the scene has. Two meshlets an item: a
// frame that draws a few pages (a spot light's face as the camera moves) spreads them over many
// workgroups instead of a few long ones (measured on an H100, docs/performance.md: the orbit's p95 of
// 3.37 ms with 8 an item fell to 3.16, the turning sun's median from 2.89 to 2.71 ms).
PENUMBRA_CONST(uint, kRasterBatch, 128u)
PENUMBRA_CONST(uint, kRasterMeshletsPerItem, 2u)
PENUMBRA_CONST(uint, kRasterInitialWork, 262144u)  // 4 MiB: a million boxes ask ~73k in a 1080p orbit
// A mesh of one meshlet of T triangles is packed instead: one item holds up to kRasterPackTriangles / T
// (at most kRasterPackInstances) of the tile's instances of it (a box's 12 triangles: 21), so a million
// small objects are not a million workgroups of 12 busy threads.
PENUMBRA_CONST(uint, kRasterPackTriangles, 256u)
PENUMBRA_CONST(uint, kRasterPackInstances, 64u)
PENUMBRA_CONST(uint, kRasterPackedItem, 0x80000000u)
struct RasterWorkItem {
    uint instance;      // packed: the first of its slots in the tile's visible list
    uint tile;          // culling tile index
    uint meshSlot;      // CullMesh index
    uint firstMeshlet;  // of the level's meshlets; the item holds up to kRasterMeshletsPerItem from there;
                        // the level (0: the full mesh) in the bits from kRasterLodShift.
                        // Packed: kRasterPackedItem | the number of instances
};
PENUMBRA_CONST(uint, kRasterLodShift, 28u)
PENUMBRA_CONST(uint, kRasterMeshletMask, 0x0fffffffu)
PENUMBRA_CHECK_SIZE(RasterWorkItem, 16)
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

// Counters of one atlas pass: large triangles and chunks queued, and dropped (queue full, drawn by the
// thread that found them instead); the two indirect dispatches (x, y, z) sized from them; the meshlets
// skipped (render.meshletCulling): outside the view or tile, facing away.
struct RasterCounters {
    uint largeQueued;
    uint chunksQueued;
    uint largeDropped;
    uint chunksDropped;
    uvec4 largeDispatch;
    uvec4 chunkDispatch;
    uint meshletsOutside;
    uint meshletsFacingAway;
    uint workQueued;    // shadow rasterizer's pass-1 work items (RasterWorkItem) queued
    uint workDropped;   // and not drawn: the queue was full
    uvec4 workDispatch;
    uint mediumQueued;  // shadow rasterizer: pieces a pass-1 workgroup rasterized together (shadow_raster.comp)
    uint lodItems;      // shadow rasterizer: work items of a simplified level (shadowLod > 0)
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(RasterCounters, 96)
PENUMBRA_CHECK_LAYOUT(RasterCounters, largeDispatch, 16)
PENUMBRA_CHECK_LAYOUT(RasterCounters, meshletsOutside, 48)

// Push constants of the shadow rasterizer's passes (shadow_raster*.comp); the tiles come from the
// raster list (RasterTileListHeader).
struct ShadowRasterConstants {
    uint depthSide;        // texels along a row of the depth buffer (the atlas's or the page pool's side)
    uint meshletCulling;   // 1: skip meshlets outside the tile (render.meshletCulling)
    uint largeCapacity;    // large pieces the queue holds
    uint chunkCapacity;    // chunks the queue holds
    uint workCapacity;     // pass-1 work items the queue holds
    uint listsPerBuffer;   // of the culling pass's visible-instance lists
    float lodErrorTexels;  // a caster's simplified level may lie this many texels from its mesh (0: full meshes)
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(ShadowRasterConstants, 32)

// Push constants of shadow_atlas_copy.comp / shadow_atlas_resolve.comp: the rect of atlas texels a
// dispatch copies, one texel per thread in groups of kAtlasCopyGroupX x kAtlasCopyGroupY (a subgroup's
// threads along one row: its buffer reads are contiguous).
PENUMBRA_CONST(uint, kAtlasCopyGroupX, 32u)
PENUMBRA_CONST(uint, kAtlasCopyGroupY, 8u)
struct AtlasCopyConstants {
    uint originX, originY;  // the rect's first texel
    uint width, height;     // its size in texels
    uint depthSide;         // texels along a row of the depth buffer (shadow_atlas_copy.comp)
    uint reserved0, reserved1, reserved2;
};
PENUMBRA_CHECK_SIZE(AtlasCopyConstants, 32)

// Push constants of shadow_raster_args.comp, which sizes both rasterizers' indirect dispatches.
PENUMBRA_CONST(uint, kRasterArgsLarge, 0u)   // the large-piece pass (2)
PENUMBRA_CONST(uint, kRasterArgsChunks, 1u)  // the chunk pass (3)
PENUMBRA_CONST(uint, kRasterArgsWork, 2u)    // the shadow rasterizer's pass 1, over its work items
struct RasterArgsConstants {
    uint queue;  // kRasterArgs*
    uint largeCapacity;
    uint chunkCapacity;
    uint workCapacity;
};
PENUMBRA_CHECK_SIZE(RasterArgsConstants, 16)

PENUMBRA_GPU_NAMESPACE_END
#endif
