#version 460
// Tests only: evaluates the virtual shadow map lookup (penumbra/shadows/virtual_shadow_lookup.glsl) at a list of world
// points and writes each one's shadow term and serving level, so the render tests can compare the GPU
// lookup with its CPU reference (shadows/virtual_shadow_lookup.h) on the same page table and pool.
#include "virtual_shadow_probe.glsl"

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= constants.pointCount) return;
    const VirtualShadowProbePoint point = points[i];
    const VirtualShadowSample shadow = sampleVirtualShadow(lookup, point.wsPosition, point.wsFootprint);
    results[i] = VirtualShadowProbeResult(shadow.lit, shadow.level, 0u, 0u);
}
