// The draw list of a virtual shadow map (virtual_page_structs.h) as the compute rasterizer's tile lists
// (cull_structs.h), all on the GPU, shared by virtual_page_tiles.comp (a directional light's clipmap
// pages) and virtual_face_tiles.comp (spot and point light faces' pages): one thread per dirty page writes
// its CullTile (the includer's pageTile: the page's projection and its culling test; its slot's viewport
// in the record's depth target) and raster entry; thread 0 writes both headers with the dispatch sizes of the
// culling and raster passes. The rules are virtual_page_draw_structs.h's; render/virtual_page_draw_pass.cpp
// and shadows/virtual_faces.cpp have the projections on the CPU (the tests').
#ifndef PENUMBRA_VIRTUAL_PAGE_TILES_GLSL
#define PENUMBRA_VIRTUAL_PAGE_TILES_GLSL
#include "pass_bindings.h"
#include "cull_structs.h"
#include "virtual_page_structs.h"
#include "virtual_page_draw_structs.h"

layout(local_size_x = kVirtualPageGroupSize) in;

layout(set = kPassSet, binding = kPageDrawBindingDrawList, std430) readonly buffer PageDrawBlock {
    VirtualPageDrawHeader drawHeader;
    VirtualPageDraw draws[];
};
layout(set = kPassSet, binding = kPageDrawBindingTiles, std430) writeonly buffer CullTileBlock {
    CullTileListHeader tileList;
    CullTile tiles[];
};
layout(set = kPassSet, binding = kPageDrawBindingRasterList, std430) writeonly buffer RasterTileBlock {
    RasterTileListHeader rasterList;
    uint rasterEntries[];
};
layout(push_constant) uniform PageTilesBlock { VirtualPageTilesConstants constants; };

// The includer's: the tile of one listed page.
CullTile pageTile(VirtualPageDraw draw);

void writeHeaders(uint count) {
    tileList.cullDispatch = uvec4(constants.instanceGroups, count, 1u, 0u);
    tileList.drawsDispatch = uvec4(constants.meshGroups, count, 1u, 0u);
    tileList.count = count;
    uint clearGroups = (constants.pageSize + kRasterClearGroup - 1u) / kRasterClearGroup;
    rasterList.clearDispatch = uvec4(clearGroups, clearGroups, count, 0u);
    rasterList.expandDispatch = uvec4(max(constants.expandGroups, 1u), 1u, count, 0u);
    rasterList.count = count;
}

// The place where the record draws its i-th page: slot i of the depth target.
void placeInTarget(inout CullTile tile, uint slot) {
    uint size = constants.pageSize;
    uvec2 origin = uvec2(slot % constants.targetPagesPerSide, slot / constants.targetPagesPerSide) * size;
    tile.viewport = vec4(vec2(origin), float(size), float(size));
    tile.scissor = uvec4(origin, origin + size);
}

void main() {
    uint count = min(drawHeader.count, constants.capacity);
    uint i = gl_GlobalInvocationID.x;
    if (i == 0u) writeHeaders(count);
    if (i >= count) return;
    CullTile tile = pageTile(draws[i]);
    placeInTarget(tile, i);
    tiles[i] = tile;
    rasterEntries[i] = i;
}
#endif
