#version 460
// The virtual shadow map's draw list (virtual_page_structs.h) as the compute rasterizer's tile lists
// (cull_structs.h), all on the GPU: one thread per dirty page writes its CullTile (the page's orthographic
// projection, its square for the culling test, its physical page's viewport in the pool) and raster entry;
// thread 0 writes both headers with the dispatch sizes of the culling and raster passes. The rules are
// virtual_page_draw_structs.h's; render/virtual_page_draw_pass.cpp has the same on the CPU (the tests').
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

void writeHeaders(uint count) {
    tileList.cullDispatch = uvec4(constants.instanceGroups, count, 1u, 0u);
    tileList.drawsDispatch = uvec4(constants.meshGroups, count, 1u, 0u);
    tileList.count = count;
    uint clearGroups = (constants.pageSize + kRasterClearGroup - 1u) / kRasterClearGroup;
    rasterList.clearDispatch = uvec4(clearGroups, clearGroups, count, 0u);
    rasterList.expandDispatch = uvec4(max(constants.expandGroups, 1u), 1u, count, 0u);
    rasterList.count = count;
}

CullTile pageTile(VirtualPageDraw draw) {
    uint level = draw.entry / (constants.pagesPerSide * constants.pagesPerSide);
    float lsPage = constants.firstLevelSize * exp2(float(level)) / float(constants.pagesPerSide);
    vec2 lsMin = vec2(draw.pageX, draw.pageY) * lsPage;
    float near = constants.lsDepthNear, far = constants.lsDepthFar;
    mat4 clipFromLight = mat4(vec4(2.0 / lsPage, 0.0, 0.0, 0.0), vec4(0.0, 2.0 / lsPage, 0.0, 0.0),
                              vec4(0.0, 0.0, -1.0 / (near - far), 0.0),
                              vec4(-2.0 * vec2(draw.pageX, draw.pageY) - 1.0, near / (near - far), 1.0));
    mat4 rotation = constants.lightRotationFromWorld;
    CullTile tile;
    // Culling as a directional tile centred on the page: its square, every depth, no blend culling.
    tile.lightFromWorld = rotation;
    tile.lightFromWorld[3] = vec4(-(lsMin + 0.5 * lsPage), 0.0, 1.0);
    for (int i = 0; i < 5; ++i) tile.planes[i] = vec4(0.0);
    tile.frustumMin = vec3(0.0);
    tile.kind = kCullTileDirectional;
    tile.frustumMax = vec3(0.0);
    tile.reserved0 = 0.0;
    tile.halfExtent = 0.5 * lsPage;
    tile.farDistance = uintBitsToFloat(0x7f7fffffu);  // the largest float: no depth culling
    tile.cascadeIndex = 0.0;
    tile.blendCullingFactor = 0.0;
    tile.wsLightDirection = -vec3(rotation[0][2], rotation[1][2], rotation[2][2]);
    tile.slopeBias = constants.slopeBias;
    tile.clipFromWorld = clipFromLight * rotation;
    uint page = draw.physicalPage, size = constants.pageSize;
    uvec2 origin = uvec2(page % constants.poolPagesPerSide, page / constants.poolPagesPerSide) * size;
    tile.viewport = vec4(vec2(origin), float(size), float(size));
    tile.scissor = uvec4(origin, origin + size);
    return tile;
}

void main() {
    uint count = min(drawHeader.count, constants.capacity);
    uint i = gl_GlobalInvocationID.x;
    if (i == 0u) writeHeaders(count);
    if (i >= count) return;
    tiles[i] = pageTile(draws[i]);
    rasterEntries[i] = i;
}
