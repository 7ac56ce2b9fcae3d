// The spot and point lights' virtual shadow map faces in GLSL: mirrors src/shadows/virtual_faces.h
// (projectOntoFace, faceMipForFootprint, facePages) and shadows/spot_projection.h (pointLightFaceOf)
// function for function, with the same float operations, so the GPU marking agrees with its CPU
// reference. Change both together.
#ifndef PENUMBRA_VIRTUAL_FACES_GLSL
#define PENUMBRA_VIRTUAL_FACES_GLSL
#include "virtual_face_structs.h"

struct FacePoint {
    vec2 ndc;
    float depth;
    float lightDistance;
};

// False when the point lies behind the light or outside the face's frustum.
bool projectOntoFace(VirtualFaceData face, vec3 wsPosition, out FacePoint point) {
    const vec4 clip = face.clipFromWorld * vec4(wsPosition, 1.0);
    if (!(clip.w > 0.0)) return false;
    const vec3 ndc = clip.xyz / clip.w;
    if (abs(ndc.x) > 1.0 || abs(ndc.y) > 1.0 || ndc.z < 0.0 || ndc.z > 1.0) return false;
    point = FacePoint(ndc.xy, ndc.z, clip.w);
    return true;
}

// The cube-map face of the major axis of light -> point (ties to the lower axis).
uint virtualPointFaceOf(vec3 wsFromLight) {
    const vec3 a = abs(wsFromLight);
    const uint axis = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (wsFromLight[axis] < 0.0 ? 1u : 0u);
}

uint faceMipForFootprint(uint resolution, uint mipCount, float tanHalfFov, float lightDistance, float wsFootprint) {
    const float ndcFootprint = wsFootprint / (lightDistance * tanHalfFov);
    const float ndcTexel0 = 2.0 / float(resolution);
    if (!(ndcFootprint > ndcTexel0)) return 0u;
    int exponent;
    frexp(ndcFootprint / ndcTexel0, exponent);  // ratio = m * 2^exponent, m in [0.5, 1)
    return uint(min(exponent - 1, int(mipCount) - 1));
}

// The pages of mip `mip` (pagesPerSide >> mip a side) a filter reaching marginTexels around ndc reads.
void facePages(uint pagesPerSide, uint pageSize, uint mip, vec2 ndc, float marginTexels, out ivec2 minPage,
               out ivec2 maxPage) {
    const int pages = int(pagesPerSide >> mip);
    const float texels = float(pages) * float(pageSize);
    const vec2 texel = (ndc * 0.5 + 0.5) * texels;
    minPage = clamp(ivec2(floor((texel - marginTexels) / float(pageSize))), ivec2(0), ivec2(pages - 1));
    maxPage = clamp(ivec2(floor((texel + marginTexels) / float(pageSize))), ivec2(0), ivec2(pages - 1));
}
#endif
