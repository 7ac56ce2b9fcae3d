// The spot and point lights' virtual page marking, per pixel (shared by virtual_face_mark.comp, the
// main view's depth texture, and virtual_face_mark_visibility.comp, the visibility buffer's depth): for
// every light whose face holds the pixel's surface, the request bits of the pages its shadow lookup reads
// (its footprint's mip with the filter's reach) and of the mip kVirtualPageFallbackLevels coarser. The CPU
// reference, shadows/virtual_faces.cpp markVirtualFacePages, does the same with the same operations.
#ifndef PENUMBRA_VIRTUAL_FACE_MARK_GLSL
#define PENUMBRA_VIRTUAL_FACE_MARK_GLSL
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "pixel_position.glsl"
#include "penumbra/shadows/virtual_faces.glsl"

layout(set = kPassSet, binding = kFaceMarkBindingFrame, std140) uniform FaceMarkBlock { VirtualFaceMarkData mark; };
layout(set = kPassSet, binding = kFaceMarkBindingRequests, std430) buffer FaceRequestBlock { uint requestWords[]; };
layout(set = kPassSet, binding = kFaceMarkBindingFaces, std430) readonly buffer FaceBlock { VirtualFaceData faces[]; };
layout(set = kPassSet, binding = kFaceMarkBindingLights, std430) readonly buffer FaceLightBlock {
    VirtualFaceLightData faceLights[];
};

void requestFacePages(uint mip, uint face, vec2 ndc) {
    ivec2 minPage, maxPage;
    facePages(mark.pagesPerSide, mark.pageSize, mip, ndc, mark.marginTexels, minPage, maxPage);
    const uint level = mip * mark.faceCount + face;
    for (int y = minPage.y; y <= maxPage.y; ++y)
        for (int x = minPage.x; x <= maxPage.x; ++x) {
            const uint bit = virtualPageBit(level, mark.pagesPerSide, uint(x), uint(y));
            const uint word = bit / 32u, mask = 1u << (bit % 32u);
            if (word >= mark.requestWordCount || (requestWords[word] & mask) != 0u) continue;  // most find it set
            atomicOr(requestWords[word], mask);
        }
}

void markFacePixel(uvec2 p, float depth) {
    if (!(depth > 0.0)) return;  // reversed Z: 0 = nothing drawn
    const vec3 wsPosition = wsPositionOfPixel(mark.worldFromClip, p, mark.width, mark.height, depth);
    const float vsDepth = -(mark.viewFromWorld * vec4(wsPosition, 1.0)).z;
    const float wsFootprint = vsDepth * mark.wsFootprintPerDepth;
    for (uint i = 0u; i < mark.lightCount; ++i) {
        const VirtualFaceLightData light = faceLights[i];
        uint face = light.firstFace;
        if (light.point != 0u) face += virtualPointFaceOf(wsPosition - faces[light.firstFace].wsPosition);
        if (face >= mark.faceCount) continue;
        FacePoint point;
        if (!projectOntoFace(faces[face], wsPosition, point)) continue;
        const uint mip = faceMipForFootprint(mark.resolution, mark.mipCount, faces[face].tanHalfFov, point.lightDistance,
                                             wsFootprint);
        requestFacePages(mip, face, point.ndc);
        const uint fallback = min(mip + kVirtualPageFallbackLevels, mark.mipCount - 1u);
        if (fallback != mip) requestFacePages(fallback, face, point.ndc);
    }
}
#endif
