#version 460
// Copies the pages of the draw list from the pool's depth buffer (float bits, the compute rasterizer's
// atomic-min target) into the pool's R32F image that later passes sample: one workgroup per listed page
// (VirtualPageDrawHeader::pageDispatch), its physical page's texels only, so the other pages keep theirs.
// The image may hold several maps' pools (render/virtual_page_storage.h): this one starts at row poolOriginY.
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "virtual_page_draw_structs.h"

layout(local_size_x = kVirtualPageCopyGroup, local_size_y = kVirtualPageCopyGroup) in;

layout(set = kPassSet, binding = kPageDrawBindingDrawList, std430) readonly buffer PageDrawBlock {
    VirtualPageDrawHeader drawHeader;
    VirtualPageDraw draws[];
};
layout(set = kPassSet, binding = kPageDrawBindingPoolDepth, std430) readonly buffer PoolDepthBlock { uint poolDepth[]; };
layout(set = kPassSet, binding = kPageDrawBindingPoolTexture, r32f) uniform writeonly image2D poolTexture;
layout(push_constant) uniform PageCopyBlock { VirtualPageCopyConstants constants; };

void main() {
    uint index = gl_WorkGroupID.x;
    if (index >= min(drawHeader.count, constants.capacity)) return;
    uint page = draws[index].physicalPage, size = constants.pageSize;
    uvec2 origin = uvec2(page % constants.poolPagesPerSide, page / constants.poolPagesPerSide) * size;
    uint side = constants.poolPagesPerSide * size;
    for (uint y = gl_LocalInvocationID.y; y < size; y += kVirtualPageCopyGroup)
        for (uint x = gl_LocalInvocationID.x; x < size; x += kVirtualPageCopyGroup) {
            uvec2 texel = origin + uvec2(x, y);  // pool depth buffer texels
            ivec2 target = ivec2(texel + uvec2(0u, constants.poolOriginY));  // pool texture texels
            imageStore(poolTexture, target, vec4(uintBitsToFloat(poolDepth[texel.y * side + texel.x])));
        }
}
