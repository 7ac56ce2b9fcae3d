// What the lit pass reads of the virtual shadow maps (penumbra/shadows/virtual_shadows.glsl): the directional
// lights' (shadows.directional.mode = virtual; render/virtual_shadows.h) and the spot and point lights'
// faces (shadows.spot.mode = virtual; render/virtual_face_shadows.h), shared by C++ and GLSL.
#ifndef PENUMBRA_VIRTUAL_LIT_STRUCTS_H
#define PENUMBRA_VIRTUAL_LIT_STRUCTS_H
#include "gpu_shared.h"
#include "virtual_face_structs.h"
#include "virtual_shadow_structs.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// One uniform block: whether directional lights sample virtual maps, the footprint rule the marking pass
// used (so a pixel reads the level whose pages were requested for it) and each shadow slot's lookup.
struct VirtualDirectionalShadowData {
    uint enabled;               // 1: every shadowed directional light samples maps[its shadow slot]
    float wsFootprintPerDepth;  // a pixel's world footprint per unit of view depth
    uint mapCount;              // maps[0 .. mapCount) are valid
    uint reserved0;
    // By shadow slot: the footprint's scale, 2^lodBias or 2^movingLodBias (a light that turns): the
    // marking pass's wsFootprintPerDepth is wsFootprintPerDepth x footprintScales[slot].
    vec4 footprintScales;
    VirtualShadowLookupData maps[4];  // kMaxShadowedDirectionalLights, by shadow slot
};
PENUMBRA_CHECK_SIZE(VirtualDirectionalShadowData, 32 + 4 * (112 + 16 * 16))
PENUMBRA_CHECK_LAYOUT(VirtualDirectionalShadowData, maps, 32)

// One uniform block for the spot and point lights' faces: whether they sample virtual maps, the footprint
// rule of their marking pass, their page table (faceCount > 0) and the faces. A shadow slot's faces start
// at OtherShadowLight::firstTile.
struct VirtualFaceShadowData {
    uint enabled;               // 1: every shadowed spot and point light samples its faces
    float wsFootprintPerDepth;  // a pixel's world footprint per unit of view depth (VirtualFaceMarkData's)
    uint reserved0;
    uint reserved1;
    VirtualShadowLookupData table;
    VirtualFaceData faces[16];  // kMaxOtherShadowTiles; table.faceCount are valid
};
PENUMBRA_CHECK_SIZE(VirtualFaceShadowData, 16 + (112 + 16 * 16) + 16 * 80)
PENUMBRA_CHECK_LAYOUT(VirtualFaceShadowData, faces, 16 + 112 + 16 * 16)

PENUMBRA_GPU_NAMESPACE_END
#endif
