#version 460
// Copies the pages of the draw list from the record's depth target (float bits, the compute rasterizer's
// atomic-min buffer; listed page i in slot i) into their physical pages of the pool's R32F image that
// later passes sample: one workgroup per listed page (VirtualPageDrawHeader::pageDispatch), its physical
// page's texels only, so the other pages keep theirs.
// The image may hold several maps' pools (render/virtual_page_storage.h): this one starts at row poolOriginY.
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "virtual_page_draw_structs.h"

layout(local_size_x = kVirtualPageCopyGroup, local_size_y = kVirtualPageCopyGroup) in;

layout(set = kPassSet, binding = kPageDrawBindingDrawList, std430) readonly buffer PageDrawBlock {
    VirtualPageDrawHeader drawHeader;
    VirtualPageDraw draws[];
};
layout(set = kPassSet, binding = kPageDrawBindingTargetDepth, std430) readonly buffer TargetDepthBlock { uint targetDepth[]; };
layout(set = kPassSet, binding = kPageDrawBindingPoolTexture, r32f) uniform writeonly image2D poolTexture;
layout(push_constant) uniform PageCopyBlock { VirtualPageCopyConstants constants; };

void main() {
    uint index = gl_WorkGroupID.x;
    if (index >= min(drawHeader.count, constants.capacity)) return;
    uint page = draws[index].physicalPage, size = constants.pageSize, slots = constants.targetPagesPerSide;
    uvec2 from = uvec2(index % slots, index / slots) * size;  // depth target texels
    uvec2 to = uvec2(page % constants.poolPagesPerSide, page / constants.poolPagesPerSide) * size + uvec2(0u, constants.poolOriginY);
    uint side = slots * size;
    for (uint y = gl_LocalInvocationID.y; y < size; y += kVirtualPageCopyGroup)
        for (uint x = gl_LocalInvocationID.x; x < size; x += kVirtualPageCopyGroup) {
            uvec2 texel = from + uvec2(x, y);
            imageStore(poolTexture, ivec2(to + uvec2(x, y)), vec4(uintBitsToFloat(targetDepth[texel.y * side + texel.x])));
        }
}
