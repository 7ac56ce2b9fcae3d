// GPU data of the spot and point light shadows (the "other" atlas), shared by C++
// (shadows/spot_shadow_planner) and GLSL (penumbra/shadows.glsl otherShadow). One uniform block per frame.
//
// Same depth convention as DirectionalShadowData (see shadow_structs.h): Vulkan clip space, standard
// depth 0 at the near plane, atlas cleared to 1, sampled with compare op LESS_OR_EQUAL. The projections
// are perspective: atlasFromWorld gives homogeneous (u w, v w, depth w, w); divide by w before sampling.
#ifndef PENUMBRA_OTHER_SHADOW_STRUCTS_H
#define PENUMBRA_OTHER_SHADOW_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kMaxOtherShadowTiles, 16u)
PENUMBRA_CONST(uint, kMaxShadowedOtherLights, 16u)

// Specialization constant "other shadow mode" of the lit pass (the _SHADOWS_HARD / _SHADOWS_SOFT keywords of
// Catlike Coding "Spotlight Shadows", Shader Keywords): bit 0 = some reserved light is hard, bit 1 = some is
// soft; 0 = no spot/point shadows.
PENUMBRA_CONST(uint, kOtherShadowsHard, 1u)
PENUMBRA_CONST(uint, kOtherShadowsSoft, 2u)
// shadows.spot.mode = virtual: the lights read their virtual faces (penumbra/shadows/virtual_face_shadows.glsl). Alone
// (no hard or soft bit) the atlas's sampling is compiled out; the generic variant has all three bits.
PENUMBRA_CONST(uint, kOtherShadowsVirtual, 4u)

// One shadowed spot or point light (a slot).
struct OtherShadowLight {
    float strength;
    uint firstTile;          // a point light's face f is tile firstTile + f, faces ordered +X, -X, +Y, -Y, +Z, -Z
    uint soft;               // 1 soft, 0 hard
    uint point;              // 1 point, 0 spot
    vec4 wsPosition;         // xyz, w unused
    vec4 wsAxis;             // xyz = spot axis (unit, the way the light travels; unused for points), w unused
    float normalBias;        // shadowNormalBias
    float slopeBias;         // shadowBias, applied in the lit pass
    float wsTexelPerDistance;  // world texel size per unit of distance along the tile's axis
    uint filterMode;         // kShadowFilter*: spot.filter for a soft light, PCF2x2 for a hard one
    float pcssRadius;        // emitter radius of a "pcss" light (its shadowLightSize; 0 = not pcss)
    float nearDistance;      // of its tiles (to turn depths into distances)
    float farDistance;
    float depthBias;         // clip-space depth bias subtracted from the receiver's clip z before the divide
};
PENUMBRA_CHECK_SIZE(OtherShadowLight, 80)

struct OtherShadowData {
    // Per tile: world -> homogeneous (atlas u, atlas v, depth, w).
    mat4 atlasFromWorld[16];
    // Per tile: (min u, min v, max u, max v) where a filter may be centred without reading outside the
    // tile's drawn interior (the 4-texel scissored border and the filter's reach excluded).
    vec4 tileBounds[16];
    OtherShadowLight lights[16];
    // The directional lights' distance fade by view depth, and the squared-distance fade's scale and
    // bias (fadeMode = kShadowFadeSquared, shadow_fade.h).
    float invShadowDistance;
    float invDistanceFade;
    float squaredFadeScale;
    float squaredFadeBias;
    uint lightCount;   // shadowed spot and point lights
    uint filterMode;   // the soft filter (kShadowFilter*)
    uint tilesUsed;
    uint split;        // tiles per atlas row
    float atlasSize;   // in texels
    float invAtlasSize;
    float tileSize;
    float invTileSize;
    uint biasMode;     // kShadowBias* (shadow_structs.h)
    uint fadeMode;     // kShadowFade*
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(OtherShadowData, 2624)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, tileBounds, 1024)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lights, 1280)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, invShadowDistance, 2560)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lightCount, 2576)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, atlasSize, 2592)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, biasMode, 2608)

PENUMBRA_GPU_NAMESPACE_END
#endif
