// GPU data of the spot and point light shadows (the "other" atlas), shared by C++
// (shadows/spot_shadow_planner) and GLSL (shadows.glsl otherShadow). One uniform block per frame.
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

struct OtherShadowData {
    // Per tile: world -> homogeneous (atlas u, atlas v, depth, w). A point light's face f is tile
    // lights[slot].y + f, faces ordered +X, -X, +Y, -Y, +Z, -Z.
    mat4 atlasFromWorld[16];
    // Per tile: (min u, min v, max u, max v) where a filter may be centred without reading outside the
    // tile's drawn interior (the 4-texel scissored border and the filter's reach excluded).
    vec4 tileBounds[16];
    // Per shadowed light slot: x = strength, y = first tile, z = 1 soft / 0 hard, w = 1 point / 0 spot.
    vec4 lights[16];
    // Per slot: xyz = light position, w unused.
    vec4 lightPositions[16];
    // Per slot: xyz = spot axis (unit, the direction the light travels; unused for points), w = constant
    // clip-space depth bias subtracted from the receiver's clip z before the divide (spot.depthBias).
    vec4 lightDirections[16];
    // x = 1 / shadow distance, y = 1 / distanceFade: the directional lights' distance fade by view depth;
    // z, w = scale and bias of the squared-distance fade (modes.y = kShadowFadeSquared, shadow_fade.h).
    vec4 fade;
    // x = shadowed light count, y = soft filter (kShadowFilter*), z = tiles used, w = split.
    uvec4 config;
    // x = atlas size in texels, y = 1 / atlas size, z = tile size, w = 1 / tile size.
    vec4 atlasSize;
    // Per slot: x = normal-bias multiplier (shadowNormalBias), y = slope-scale bias (shadowBias, applied
    // in the lit pass), z = world texel size per unit of distance along the tile's axis, w = filter
    // (kShadowFilter*: spot.filter for a soft light, PCF2x2 for a hard one).
    vec4 lightBias[16];
    // x = bias mode (kShadowBias*, shadow_structs.h), y = fade mode (0 linear, 1 squared), zw unused.
    uvec4 modes;
    // Per slot: x = emitter radius of a "pcss" light (its shadowLightSize; 0 = not pcss), y = near and
    // z = far distance of its tiles (to turn depths into distances), w unused.
    vec4 pcss[16];
};
PENUMBRA_CHECK_SIZE(OtherShadowData, 2624)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, tileBounds, 1024)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lights, 1280)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lightPositions, 1536)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lightDirections, 1792)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, fade, 2048)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, config, 2064)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, atlasSize, 2080)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, lightBias, 2096)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, modes, 2352)
PENUMBRA_CHECK_LAYOUT(OtherShadowData, pcss, 2368)

PENUMBRA_GPU_NAMESPACE_END
#endif
