#version 460
// Tests only: evaluates the spot and point lights' virtual shadow lookup (penumbra/shadows/virtual_face_lookup.glsl) of one
// light at a list of world points, writing each one's shadow term and serving level, so the render tests
// can compare the GPU lookup with its CPU reference on the same page table and pool.
#include "virtual_shadow_probe.glsl"
#include "virtual_face_structs.h"

layout(set = kPassSet, binding = kShadowProbeBindingFaces, std430) readonly buffer ShadowProbeFaceBlock { VirtualFaceData faces[]; };

#include "penumbra/shadows/virtual_face_lookup.glsl"

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= constants.pointCount) return;
    const VirtualShadowProbePoint point = points[i];
    uint face = constants.firstFace;
    if (constants.point != 0u) face += virtualPointFaceOf(point.wsPosition - faces[face].wsPosition);
    const VirtualShadowSample shadow = sampleVirtualFace(lookup, faces[face], face, point.wsPosition, point.wsFootprint);
    results[i] = VirtualShadowProbeResult(shadow.lit, shadow.level, 0u, 0u);
}
