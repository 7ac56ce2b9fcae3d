// Copies the pages of the draw list from the record's depth target (float bits, the compute rasterizer's
// atomic-min buffer; listed page i in slot i) into their physical pages of the pool image that later
// passes sample, as 16-bit codes relative to the page's own depth range (virtual_page_structs.h, "The
// pool's texels"), and writes that range into the page's entry: one workgroup per listed page
// (VirtualPageDrawHeader::pageDispatch), its physical page's texels only, so the other pages keep theirs.
// The image may hold several maps' pools (render/virtual_page_storage.h): this one starts at row poolOriginY.
// The includer names the image's format: PENUMBRA_POOL_FORMAT (r16 or r32f).
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "virtual_page_draw_structs.h"

layout(local_size_x = kVirtualPageCopyGroup, local_size_y = kVirtualPageCopyGroup) in;

layout(set = kPassSet, binding = kPageDrawBindingDrawList, std430) readonly buffer PageDrawBlock {
    VirtualPageDrawHeader drawHeader;
    VirtualPageDraw draws[];
};
layout(set = kPassSet, binding = kPageDrawBindingTargetDepth, std430) readonly buffer TargetDepthBlock { uint targetDepth[]; };
layout(set = kPassSet, binding = kPageDrawBindingPoolTexture, PENUMBRA_POOL_FORMAT) uniform writeonly image2D poolTexture;
layout(set = kPassSet, binding = kPageDrawBindingEntries, std430) buffer EntryBlock { VirtualPageEntry entries[]; };
layout(push_constant) uniform PageCopyBlock { VirtualPageCopyConstants constants; };

// The page's nearest and farthest drawn depths as float bits: depths in [0, 1) order as their bits do.
shared uint pageMinBits;
shared uint pageMaxBits;

// Depths nearer than the map's near plane were clamped to 0 when drawn (pancaking); clamp again here.
float targetTexel(uvec2 texel, uint side) { return max(uintBitsToFloat(targetDepth[texel.y * side + texel.x]), 0.0); }

// The code of `depth` (virtual_page_structs.h): rounded up, and one more where the division's rounding
// left it a hair short, so that it never decodes nearer than drawn (shadows/virtual_page_depth.cpp does
// the same).
uint depthCode(float depth, float depthMin, float depthStep) {
    if (!(depth < 1.0)) return kVirtualPageDepthCodeFar;
    if (!(depthStep > 0.0)) return 0u;
    uint code = min(uint(ceil((depth - depthMin) / depthStep)), kVirtualPageDepthCodeMax);
    if (code < kVirtualPageDepthCodeMax && virtualPageDecodeDepth(code, depthMin, depthStep) < depth) ++code;
    return code;
}

void main() {
    const uint index = gl_WorkGroupID.x;
    if (index >= min(drawHeader.count, constants.capacity)) return;
    const uint page = draws[index].physicalPage, size = constants.pageSize, slots = constants.targetPagesPerSide;
    const uvec2 from = uvec2(index % slots, index / slots) * size;  // depth target texels
    const uint side = slots * size;
    const bool first = gl_LocalInvocationIndex == 0u;
    if (first) {
        pageMinBits = floatBitsToUint(1.0);
        pageMaxBits = 0u;
    }
    barrier();
    uint minBits = floatBitsToUint(1.0), maxBits = 0u;
    for (uint y = gl_LocalInvocationID.y; y < size; y += kVirtualPageCopyGroup)
        for (uint x = gl_LocalInvocationID.x; x < size; x += kVirtualPageCopyGroup) {
            const float depth = targetTexel(from + uvec2(x, y), side);
            if (depth < 1.0) {
                minBits = min(minBits, floatBitsToUint(depth));
                maxBits = max(maxBits, floatBitsToUint(depth));
            }
        }
    atomicMin(pageMinBits, minBits);
    atomicMax(pageMaxBits, maxBits);
    barrier();
    const float depthMin = uintBitsToFloat(pageMinBits);
    const float depthStep = pageMaxBits == 0u || pageMinBits >= pageMaxBits
                                ? 0.0 : (uintBitsToFloat(pageMaxBits) - depthMin) / float(kVirtualPageDepthCodeMax);
    if (first) {
        entries[draws[index].entry].depthMin = depthMin;
        entries[draws[index].entry].depthStep = depthStep;
    }
    const uvec2 to = uvec2(page % constants.poolPagesPerSide, page / constants.poolPagesPerSide) * size +
                     uvec2(0u, constants.poolOriginY);  // pool texels
    for (uint y = gl_LocalInvocationID.y; y < size; y += kVirtualPageCopyGroup)
        for (uint x = gl_LocalInvocationID.x; x < size; x += kVirtualPageCopyGroup) {
            const uint code = depthCode(targetTexel(from + uvec2(x, y), side), depthMin, depthStep);
            imageStore(poolTexture, ivec2(to + uvec2(x, y)), vec4(virtualPageTexelOfCode(code)));
        }
}
