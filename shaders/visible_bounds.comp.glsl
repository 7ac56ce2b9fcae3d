#version 460
// The tight cascade fit's depth reduction (SDSM, "Sample Distribution Shadow Maps", Lauritzen et al.
// 2011) on the GPU: every pixel of the view's depth back to world space, then the view-depth range
// and, per log-spaced view-depth bin, the bounds in each space of VisibleBoundsData
// (visible_bounds_structs.h; shadows/visible_surfaces.h reads them). The pixels of a subgroup reduce
// together per bin (a loop over the bins it holds, usually one or two) before one atomic per word.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "pass_bindings.h"
#include "visible_bounds_structs.h"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kVisibleBoundsBindingData, std140) uniform VisibleBoundsBlock { VisibleBoundsData bounds; };
layout(set = kPassSet, binding = kVisibleBoundsBindingDepth) uniform sampler2D sceneDepth;
layout(set = kPassSet, binding = kVisibleBoundsBindingWords, std430) buffer VisibleBoundsWords { uint words[]; };

// A uint that orders as the float does (negative floats reversed, below the positive ones).
uint visibleBoundsKey(float value) {
    const uint bits = floatBitsToUint(value);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= bounds.width || p.y >= bounds.height) return;
    const float depth = texelFetch(sceneDepth, ivec2(p), 0).r;
    if (!(depth > 0.0)) return;  // reversed Z: 0 = nothing drawn
    // Pixel centre to world space as shadows/visible_surfaces.cpp's wsPositionFromDepth.
    const vec2 ndc = 2.0 * (vec2(p) + 0.5) / vec2(bounds.width, bounds.height) - 1.0;
    const vec4 h = bounds.worldFromClip * vec4(ndc, depth, 1.0);
    const vec3 wsPoint = h.xyz / h.w;
    const float vsDepth = dot(bounds.vsDepthRow, vec4(wsPoint, 1.0));

    const float vsNearest = subgroupMin(vsDepth), vsFarthest = subgroupMax(vsDepth);
    if (subgroupElect()) {
        atomicMin(words[0], visibleBoundsKey(vsNearest));
        atomicMax(words[kVisibleBoundsMinWords], visibleBoundsKey(vsFarthest));
    }
    const uint bin = visibleDepthBin(vsDepth, bounds.vsBinNear, bounds.binsPerLogDepth);
    for (;;) {
        if (subgroupBroadcastFirst(bin) != bin) continue;  // a later round takes this bin
        for (uint space = 0u; space < bounds.spaceCount; ++space) {
            const vec3 rsPoint = mat3(bounds.spaceFromWorld[space]) * wsPoint;
            const vec3 rsMin = subgroupMin(rsPoint), rsMax = subgroupMax(rsPoint);
            if (subgroupElect()) {
                const uint first = 1u + (space * kVisibleDepthBins + bin) * 3u;
                for (uint axis = 0u; axis < 3u; ++axis) {
                    atomicMin(words[first + axis], visibleBoundsKey(rsMin[axis]));
                    atomicMax(words[kVisibleBoundsMinWords + first + axis], visibleBoundsKey(rsMax[axis]));
                }
            }
        }
        break;
    }
}
