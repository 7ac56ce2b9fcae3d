// The shadow lookup of spot and point lights' virtual maps: mirrors src/shadows/virtual_shadow_lookup.h
// sampleVirtualFace with the same float operations (the render tests compare the two on pages the GPU
// drew). The includer includes virtual_shadow_lookup.glsl first (its page table and pool reads) and
// picks the face: a spot light's one, or a point light's face of the major axis (virtualPointFaceOf).
#ifndef PENUMBRA_VIRTUAL_FACE_LOOKUP_GLSL
#define PENUMBRA_VIRTUAL_FACE_LOOKUP_GLSL
#include "virtual_faces.glsl"

// The mip that serves a receiver at `point` of face `face` whose pixel covers wsFootprint metres: its
// footprint's mip, or the first coarser one whose page holding it is ready; -1 when none is.
int virtualFaceReceiverMip(VirtualShadowLookupData data, VirtualFaceData faceData, uint face, FacePoint point,
                           float wsFootprint) {
    const uint mipCount = data.levelCount / data.faceCount;
    for (uint mip = faceMipForFootprint(data.resolution, mipCount, faceData.tanHalfFov, point.lightDistance, wsFootprint);
         mip < mipCount; ++mip) {
        const vec2 t = (point.ndc * 0.5 + 0.5) * float(data.resolution >> mip);  // the mip's texels
        if (virtualShadowReadyPage(data, mip * data.faceCount + face, virtualShadowPageOfTexel(data, ivec2(floor(t)))) >= 0)
            return int(mip);
    }
    return -1;
}

// The lookup at receiver wsPosition (biases applied) on face `face` (its index in the table) whose pixel
// covers wsFootprint metres: the mip of virtualFaceReceiverMip, the 2 x 2 compare there.
VirtualShadowSample sampleVirtualFace(VirtualShadowLookupData data, VirtualFaceData faceData, uint face, vec3 wsPosition,
                                      float wsFootprint) {
    FacePoint point;
    if (!projectOntoFace(faceData, wsPosition, point)) return VirtualShadowSample(1.0, kVirtualShadowNoLevel);
    const int mip = virtualFaceReceiverMip(data, faceData, face, point, wsFootprint);
    if (mip < 0) return VirtualShadowSample(1.0, kVirtualShadowNoLevel);
    const uint level = uint(mip) * data.faceCount + face;
    const vec2 t = (point.ndc * 0.5 + 0.5) * float(data.resolution >> uint(mip));
    return VirtualShadowSample(virtualShadowBilinearLit(data, level, t, point.depth), int(level));
}
#endif
