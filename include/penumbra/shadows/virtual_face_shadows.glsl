// Spot and point light shadows from their virtual shadow maps (shadows.spot.mode = virtual), for the lit
// pass and the visibility resolve: the face a receiver reads (a spot light's one, a point light's face of
// the major axis), the mip its footprint picks or the first coarser ready one (virtual_face_lookup.glsl,
// the marking pass's rule), the biases of bias.glsl with that mip's texel, and the light's filter
// (tent, 2 x 2 or PCSS) over the mip's texels through the page table, so filters read across page borders
// and fall back to a coarser mip where a page is missing (Unreal Engine's "Virtual Shadow Maps"
// documentation: local lights' virtual maps with mips picked by the pixel's footprint).
//
// A mip is treated as one perspective shadow map whose "atlas" coordinates are its texels
// (virtualFaceTexelsFromWorld; atlas size 1), so the bias and filter code is the atlas tiles' own.
#ifndef PENUMBRA_VIRTUAL_FACE_SHADOWS_GLSL
#define PENUMBRA_VIRTUAL_FACE_SHADOWS_GLSL
#include "other_shadow_structs.h"
#include "virtual_shadows.glsl"
#include "virtual_face_lookup.glsl"

// World -> homogeneous (texel x w, texel y w, depth w, w) of a face's mip `texels` texels wide: NDC x in
// [-1, 1] is texel (0.5 x + 0.5) texels, y likewise (the pages' rows go with NDC y).
mat4 virtualFaceTexelsFromWorld(VirtualFaceData face, uint texels) {
    float half_ = 0.5 * float(texels);
    mat4 texelsFromClip = mat4(vec4(half_, 0.0, 0.0, 0.0), vec4(0.0, half_, 0.0, 0.0), vec4(0.0, 0.0, 1.0, 0.0),
                               vec4(half_, half_, 0.0, 1.0));
    return texelsFromClip * face.clipFromWorld;
}

// The shadow term (1 lit, 0 shadowed; before strength and fades) of spot or point light `light` at a
// receiver `viewDepth` from the camera; `level` is the table level that served it (-1: none, lit).
float sampleOtherVirtual(OtherShadowLight light, uint biasMode, ShadowReceiver receiver, vec3 wsToLight, float viewDepth,
                         out int level) {
    level = -1;
    VirtualShadowLookupData data = virtualFaces.table;
    vec3 wsFromLight = receiver.wsPosition - light.wsPosition.xyz;
    uint face = light.firstTile + (light.point != 0u ? virtualPointFaceOf(wsFromLight) : 0u);
    if (face >= data.faceCount) return 1.0;  // no face this frame: nothing cast
    VirtualFaceData faceData = virtualFaces.faces[face];
    FacePoint point;
    if (!projectOntoFace(faceData, receiver.wsPosition, point)) return 1.0;  // outside the cone, beyond the range
    int mip = virtualFaceReceiverMip(data, faceData, face, point, viewDepth * virtualFaces.wsFootprintPerDepth);
    if (mip < 0) return 1.0;
    level = mip * int(data.faceCount) + int(face);
    uint texels = data.resolution >> uint(mip);
    float texelPerDistance = 2.0 * faceData.tanHalfFov / float(texels);  // world texel per metre along the axis
    ShadowBiasParams bias = ShadowBiasParams(biasMode, light.normalBias, light.slopeBias, texelPerDistance * point.lightDistance,
                                             normalOffsetFootprint(light.filterMode), light.depthBias);
    vec3 wsLookup = biasedLookupPosition(receiver, wsToLight, bias);
    ShadowLookup lookup = shadowLookup(virtualFaceTexelsFromWorld(faceData, texels), receiver, wsLookup, wsToLight, bias, 1.0);
    if (lookup.w <= 0.0 || lookup.uvDepth.z >= 1.0) return 1.0;  // behind the light or beyond its range
    if (light.pcssRadius > 0.0) {
        PcssLight pcss = PcssLight(1.0, vec4(light.pcssRadius, light.nearDistance, light.farDistance, texelPerDistance));
        return virtualShadowPcss(data, uint(level), lookup, pcss);
    }
    return virtualShadowFiltered(data, uint(level), lookup.uvDepth, light.filterMode, lookup.depthGradient,
                                 lookup.perTexelPlane);
}
#endif
