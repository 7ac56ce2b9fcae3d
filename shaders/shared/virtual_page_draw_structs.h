// Drawing the virtual shadow map's dirty pages (render/virtual_page_draw_pass.h), shared by C++ and GLSL
// (virtual_page_tiles.comp, virtual_page_copy.comp). The page table's draw list (virtual_page_structs.h
// VirtualPageDrawHeader + VirtualPageDraw[]) becomes the compute rasterizer's tile lists (cull_structs.h),
// one tile per dirty page:
// - its square: page (pageX, pageY) of level `entry / pagesPerSide^2` covers light-space x in
//   [pageX, pageX + 1) * lsPageSize and y in [pageY, pageY + 1) * lsPageSize, lsPageSize =
//   firstLevelSize * 2^level / pagesPerSide (shadows/virtual_clipmap.h); texel (tx, ty) of the page covers
//   [tx, tx + 1) and [ty, ty + 1) texels from that corner (rows go with light-space y);
// - its depth: light-space z (clipmapRotationFromWorld: the light travels along -z) mapped linearly from
//   lsDepthNear (depth 0) to lsDepthFar (depth 1), the same two planes for every page of every level and
//   every frame, so depths compare across pages and a cached page stays valid; casters nearer the light
//   than lsDepthNear clamp to 0 (pancaking, as the cascades);
// - its place while drawn: the i-th page of a record is drawn into slot i of the record's depth target
//   (the compute rasterizer's atomic-min buffer, targetPagesPerSide^2 slots of pageSize^2 texels), the
//   pageSize^2 texels at ((i % targetPagesPerSide), (i / targetPagesPerSide)) * pageSize;
// - its place in the pool: physical page p is the pageSize^2 texels at ((p % poolPagesPerSide),
//   (p / poolPagesPerSide)) * pageSize plus (0, poolOriginY) of the pool's texels, which several maps may
//   share (render/virtual_page_storage.h: each map's pool a square at its own rows); the copy step moves
//   slot i there as 16-bit codes of the page's own depth range (virtual_page_structs.h, "The pool's
//   texels"), and writes the range into the page's entry. The target
//   holds one record's pages, not the pool's: the pool is one image.
#ifndef PENUMBRA_VIRTUAL_PAGE_DRAW_STRUCTS_H
#define PENUMBRA_VIRTUAL_PAGE_DRAW_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kVirtualPageCopyGroup, 16u)  // virtual_page_copy.comp: 16 x 16 threads per page

// Push constants of virtual_page_tiles.comp.
struct VirtualPageTilesConstants {
    mat4 lightRotationFromWorld;  // the clipmap's space (shadows/virtual_clipmap.h clipmapRotationFromWorld)
    float lsDepthNear;            // light-space z of depth 0 (toward the light)
    float lsDepthFar;             // light-space z of depth 1
    float firstLevelSize;         // metres along level 0's side
    float slopeBias;              // the tiles' slope-scale depth bias
    uint pagesPerSide;            // of a level (resolution / pageSize)
    uint pageSize;                // texels along a page's side
    uint targetPagesPerSide;      // the depth target holds targetPagesPerSide^2 pages (slot i: the i-th listed page)
    uint capacity;                // pages the tile lists hold
    uint instanceGroups;          // the culling dispatch's x: ceil(instances / kCullWorkgroupSize)
    uint meshGroups;              // the draw lists' dispatch's x: ceil(meshes / kCullWorkgroupSize)
    uint expandGroups;            // the compute rasterizer's expansion dispatch's x: ceil(instances / kRasterExpandGroup)
    uint faceCount;               // virtual_face_tiles.comp: the faces of the table (level = mip * faceCount + face)
};
PENUMBRA_CHECK_SIZE(VirtualPageTilesConstants, 112)
PENUMBRA_CHECK_LAYOUT(VirtualPageTilesConstants, lsDepthNear, 64)
PENUMBRA_CHECK_LAYOUT(VirtualPageTilesConstants, pagesPerSide, 80)
PENUMBRA_CHECK_LAYOUT(VirtualPageTilesConstants, instanceGroups, 96)

// Push constants of virtual_page_copy.comp.
struct VirtualPageCopyConstants {
    uint pageSize;
    uint poolPagesPerSide;
    uint capacity;            // pages a draw list may hold here
    uint poolOriginY;         // pool texture rows: the pool's page 0 lies at (0, poolOriginY) (a shared texture)
    uint targetPagesPerSide;  // the depth target's slots per side (VirtualPageTilesConstants)
};
PENUMBRA_CHECK_SIZE(VirtualPageCopyConstants, 20)

PENUMBRA_GPU_NAMESPACE_END
#endif
