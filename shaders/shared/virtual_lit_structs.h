// What the lit pass reads of the directional lights' virtual shadow maps (shaders/virtual_shadows.glsl;
// shadows.directional.mode = virtual), shared by C++ (render/virtual_shadows.h) and GLSL.
#ifndef PENUMBRA_VIRTUAL_LIT_STRUCTS_H
#define PENUMBRA_VIRTUAL_LIT_STRUCTS_H
#include "gpu_shared.h"
#include "virtual_shadow_structs.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// One uniform block: whether directional lights sample virtual maps, the footprint rule the marking pass
// used (so a pixel reads the level whose pages were requested for it) and each shadow slot's lookup.
struct VirtualDirectionalShadowData {
    uint enabled;               // 1: every shadowed directional light samples maps[its shadow slot]
    float wsFootprintPerDepth;  // a pixel's world footprint per unit of view depth (VirtualPageMarkData's)
    uint mapCount;              // maps[0 .. mapCount) are valid
    uint reserved0;
    VirtualShadowLookupData maps[4];  // kMaxShadowedDirectionalLights, by shadow slot
};
PENUMBRA_CHECK_SIZE(VirtualDirectionalShadowData, 16 + 4 * (112 + 16 * 16))

PENUMBRA_GPU_NAMESPACE_END
#endif
