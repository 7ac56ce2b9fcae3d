#version 460
// Tests only: evaluates the virtual shadow map lookup (virtual_shadow_lookup.glsl) at a list of world
// points and writes each one's shadow term and serving level, so the render tests can compare the GPU
// lookup with its CPU reference (shadows/virtual_shadow_lookup.h) on the same page table and pool.
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "virtual_shadow_structs.h"

layout(local_size_x = kVirtualShadowProbeGroup) in;

layout(set = kPassSet, binding = kShadowProbeBindingLookup, std140) uniform ShadowProbeLookupBlock { VirtualShadowLookupData lookup; };
layout(set = kPassSet, binding = kShadowProbeBindingEntries, std430) readonly buffer ShadowProbeEntryBlock { VirtualPageEntry entries[]; };
layout(set = kPassSet, binding = kShadowProbeBindingPool) uniform sampler2D pool;
layout(set = kPassSet, binding = kShadowProbeBindingPoints, std430) readonly buffer ShadowProbePointBlock { VirtualShadowProbePoint points[]; };
layout(set = kPassSet, binding = kShadowProbeBindingResults, std430) writeonly buffer ShadowProbeResultBlock {
    VirtualShadowProbeResult results[];
};
layout(push_constant) uniform ShadowProbeBlock { VirtualShadowProbeConstants constants; };

// `record` counts from the bound buffer's start (the lookup adds its firstEntry): entryCount bounds it.
VirtualPageEntry virtualShadowEntry(uint record) {
    if (record < constants.entryCount) return entries[record];
    return VirtualPageEntry(kVirtualPageNone, 0u, 0, 0, 0u, 0u, 0u, 0u);
}

float virtualShadowPoolTexel(ivec2 poolTexel) { return texelFetch(pool, poolTexel, 0).r; }

#include "virtual_shadow_lookup.glsl"

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= constants.pointCount) return;
    const VirtualShadowProbePoint point = points[i];
    const VirtualShadowSample shadow = sampleVirtualShadow(lookup, point.wsPosition, point.wsFootprint);
    results[i] = VirtualShadowProbeResult(shadow.lit, shadow.level, 0u, 0u);
}
