// Tests only: what the virtual shadow lookup probes (virtual_shadow_probe.comp, virtual_face_probe.comp)
// share: the lookup data, the entries and the pool they read, the points and the results, and the page
// table and pool reads that penumbra/shadows/virtual_shadow_lookup.glsl asks of its includer.
#ifndef PENUMBRA_VIRTUAL_SHADOW_PROBE_GLSL
#define PENUMBRA_VIRTUAL_SHADOW_PROBE_GLSL
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
// One table is bound, whichever kind the lookup data names.
VirtualPageEntry virtualShadowEntry(bool faces, uint record) {
    if (record < constants.entryCount) return entries[record];
    return VirtualPageEntry(kVirtualPageNone, 0u, 0, 0, 0u, 0.0, 0.0, 0u);
}

float virtualShadowPoolTexel(bool faces, ivec2 poolTexel) { return texelFetch(pool, poolTexel, 0).r; }

#include "penumbra/shadows/virtual_shadow_lookup.glsl"
#endif
