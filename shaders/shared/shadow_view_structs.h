// The camera and the light table of <penumbra/shadows.glsl>, shared by C++ (the renderer and
// ShadowSystem pack them) and GLSL; installed with it.
#ifndef PENUMBRA_SHADOW_VIEW_STRUCTS_H
#define PENUMBRA_SHADOW_VIEW_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kNoShadowSlot, 0xffffffffu)  // a light without shadows

PENUMBRA_CONST(uint, kLightDirectional, 0u)
PENUMBRA_CONST(uint, kLightSpot, 1u)
PENUMBRA_CONST(uint, kLightPoint, 2u)

// What the shadow lookups need of the camera: view depth (cascade selection, fades) and the distance
// to the camera (the squared distance fade).
struct ShadowViewData {
    mat4 viewFromWorld;
    vec4 wsCameraPosition;  // w = 1
    uint lightCount;        // entries of the light table (penumbraShadow's light index is below it)
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(ShadowViewData, 96)

// One entry of the light table, per light in the caller's order (Scene::lights): its kind and its slot in
// DirectionalShadowData (directional) or OtherShadowData (spot, point), kNoShadowSlot when it has none.
struct ShadowLightSlot {
    uint type;  // kLight*
    uint slot;
};
PENUMBRA_CHECK_SIZE(ShadowLightSlot, 8)

PENUMBRA_GPU_NAMESPACE_END

#endif
