// The virtual shadow maps of spot and point lights (shadows/virtual_faces.h), shared by C++ and GLSL:
// the faces (one per spot light, six per point light) as the marking pass, the page drawing and the
// lookup read them, and the marking pass's uniform data. The page table is one of fixed windows
// (virtual_page_structs.h VirtualPageTableData): level = mip * faceCount + face.
#ifndef PENUMBRA_VIRTUAL_FACE_STRUCTS_H
#define PENUMBRA_VIRTUAL_FACE_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// One face (std430): its perspective projection (Vulkan clip, y down, standard depth) and the light.
struct VirtualFaceData {
    mat4 clipFromWorld;
    vec3 wsPosition;   // the light
    float tanHalfFov;  // of the frustum: the cone plus the filter's margin
};
PENUMBRA_CHECK_SIZE(VirtualFaceData, 80)
PENUMBRA_CHECK_LAYOUT(VirtualFaceData, tanHalfFov, 76)

// A light's faces (std430): a spot light's one, or a point light's six from firstFace in the cube-map
// order +X, -X, +Y, -Y, +Z, -Z (a receiver reads the face of its major axis from the light).
struct VirtualFaceLightData {
    uint firstFace;
    uint point;  // 1: six faces
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(VirtualFaceLightData, 16)

// What the faces' marking pass needs (a uniform buffer): the camera and the mip chain.
struct VirtualFaceMarkData {
    mat4 worldFromClip;         // inverse of the camera's clipFromWorld
    mat4 viewFromWorld;         // the camera's: view depth of a pixel
    float wsFootprintPerDepth;  // a pixel's world footprint per metre of view depth, times 2^lodBias
    float marginTexels;         // the filter's reach around a receiver, in texels of its mip
    uint width;                 // the depth's size
    uint height;
    uint resolution;            // virtual texels along mip 0's side
    uint pageSize;
    uint pagesPerSide;          // resolution / pageSize
    uint mipCount;
    uint faceCount;
    uint lightCount;
    uint requestWordCount;      // words of the request bits
    uint reserved;
};
PENUMBRA_CHECK_SIZE(VirtualFaceMarkData, 176)
PENUMBRA_CHECK_LAYOUT(VirtualFaceMarkData, wsFootprintPerDepth, 128)
PENUMBRA_CHECK_LAYOUT(VirtualFaceMarkData, faceCount, 160)

PENUMBRA_GPU_NAMESPACE_END
#endif
