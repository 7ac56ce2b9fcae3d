// GPU data of the directional shadows, shared by C++ (shadows/shadow_gpu_packing) and GLSL.
// Filled by penumbra::packDirectionalShadowData from a ShadowFrame; one uniform/storage block per frame.
//
// Conventions (one for the whole project's shadow maps):
// - Shadow-map clip space is Vulkan's: x right, y DOWN in NDC, z in [0, 1]. Light view space looks along
//   -Z with +Y up (like the camera), so light-space +Y lands at the top of a tile.
// - Standard depth: 0 at the near plane (closest to the light), 1 at the far plane. Clear to 1, render
//   casters with compare op LESS (or LESS_OR_EQUAL); the atlases are R32F, sampled as a sampler2D whose
//   gathered texels the shader compares LESS_OR_EQUAL: "fragment depth <= stored depth -> lit (1)".
// - atlasFromWorld maps a world position (w = 1) straight to (atlas u, atlas v, depth, 1): u, v in [0, 1]
//   over the whole atlas with v = 0 at the top row (texel row 0); orthographic, so no divide by w needed.
#ifndef PENUMBRA_SHADOW_STRUCTS_H
#define PENUMBRA_SHADOW_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kMaxShadowedDirectionalLights, 4u)
PENUMBRA_CONST(uint, kMaxCascades, 4u)
PENUMBRA_CONST(uint, kMaxDirectionalShadowTiles, 16u)

// DirectionalShadowData.filterMode mirrors ShadowFilter, .cascadeBlend mirrors CascadeBlend.
PENUMBRA_CONST(uint, kShadowFilterPcf2x2, 0u)
PENUMBRA_CONST(uint, kShadowFilterPcf3x3, 1u)
PENUMBRA_CONST(uint, kShadowFilterPcf5x5, 2u)
PENUMBRA_CONST(uint, kShadowFilterPcf7x7, 3u)
// Value of the lit pass's spot-filter specialization constant that reads the filter from
// OtherShadowData.filterMode instead: the generic variant used while a specialized one is built.
PENUMBRA_CONST(uint, kShadowFilterFromData, 4u)
// Specialization constant "directional shadow mode" of the lit pass (penumbra/shadows.glsl, constant
// PENUMBRA_SHADOW_CONSTANT_ID + 2): the sampling the frame's directional lights need, so a variant
// compiles only that (the virtual maps' page-table filters are most of the generic variant's code).
// 0 = no directional shadows; the generic variant has every bit.
PENUMBRA_CONST(uint, kDirectionalShadowsCascades, 1u)
PENUMBRA_CONST(uint, kDirectionalShadowsVirtual, 2u)
PENUMBRA_CONST(uint, kDirectionalShadowsPcss, 4u)  // some reserved directional light uses pcss
PENUMBRA_CONST(uint, kDirectionalShadowsAll, 7u)
// Its filter constant (PENUMBRA_SHADOW_CONSTANT_ID + 3) is a kShadowFilter* value where every reserved
// directional light filters alike (soft: shadows.directional.filter, hard: PCF2x2), else kShadowFilterFromData.
PENUMBRA_CONST(uint, kCascadeBlendHard, 0u)
PENUMBRA_CONST(uint, kCascadeBlendSoft, 1u)
PENUMBRA_CONST(uint, kCascadeBlendDither, 2u)

// ShadowBias.x of DirectionalShadowData and OtherShadowData mirrors ShadowBiasMode (shadows.bias):
// how the lit pass keeps a surface from shadowing itself (see penumbra/shadows.glsl shadowLookup).
PENUMBRA_CONST(uint, kShadowBiasNormal, 0u)          // constant normal offset (the classic rule)
PENUMBRA_CONST(uint, kShadowBiasScaledNormal, 1u)    // normal offset x the texel's size x sin(N, L)
PENUMBRA_CONST(uint, kShadowBiasReceiverPlane, 2u)   // each fetch compares the receiver plane's depth there

// PCSS (penumbra/shadows/pcss.glsl): the widest blocker search and filter radius, in texels; the tight fit
// keeps that many texels around the visible receivers of a pcss light.
PENUMBRA_CONST(float, kPcssMaxRadiusTexels, 24.0f)

// DirectionalShadowData.cascadeFit: how cascades were fitted and so how the lit pass selects one (shadows.directional.fit).
PENUMBRA_CONST(uint, kCascadeFitSphere, 0u)  // the first culling sphere that holds the point
PENUMBRA_CONST(uint, kCascadeFitTight, 1u)   // the first slice whose split lies beyond the point's view depth

// fadeMode: the distance fade (shadows.fadeMode).
PENUMBRA_CONST(uint, kShadowFadeLinear, 0u)   // by view depth, over the last distanceFade
PENUMBRA_CONST(uint, kShadowFadeSquared, 1u)  // URP's: by squared camera distance, scale and bias

// One unit of a light's shadowNormalBias, in texels of its shadow map: the texel diagonal x (1 + filter
// / 2), for directional, spot and point lights alike (one rule; spot lights once used 1 + filter).
// filterMode = kShadowFilter* of the light (PCF2x2 for "hard" lights). Measured in shadow_gpu_packing.cpp.
PENUMBRA_INLINE float normalOffsetFootprint(uint filterMode) { return (1.0f + 0.5f * float(filterMode)) * 1.4142136f; }

// One cascade (shared by all lights).
struct DirectionalCascade {
    // xyz = world centre, w = (r - filterSize)^2, the radius shrunk by the filter footprint so filtering
    // stays inside the tile (as SetCascadeData of Catlike Coding "Directional Shadows", PCF Filtering).
    vec4 cullingSphere;
    float invRadiusSquared;  // 1 / cullingSphere.w
    // One unit of shadowNormalBias ("shadow texels", docs/scene-format.md) in world units = texel *
    // (1 + filter / 2) * sqrt(2): the texel diagonal (as in "Directional Shadows", Normal Bias) times
    // 1 / 1.5 / 2 / 2.5 for PCF2x2 / 3x3 / 5x5 / 7x7. The tutorial (PCF Filtering) scales by filter + 1
    // (1 / 2 / 3 / 4); measured, that over-biases wide filters (thin_wall PCF7x7: 2.25 % misclassified,
    // 0.28 % interior) while half a texel per filter step already removes acne (1.47 % / 0.00 %); numbers
    // in src/shadows/shadow_gpu_packing.cpp.
    float normalBiasUnit;
    float wsTexelSize;  // 2r / tileSize
    float vsSplit;      // the view depth where the cascade's slice ends
};
PENUMBRA_CHECK_SIZE(DirectionalCascade, 32)

// One shadowed directional light (a slot).
struct DirectionalShadowLight {
    float strength;
    uint firstTile;       // its cascades' tiles follow
    float normalBias;     // shadowNormalBias: multiplies the cascade's normalBiasUnit
    uint sceneLightIndex;
    float slopeBias;      // shadowBias: depth per texel of receiver slope, applied in the lit pass
    uint filterMode;      // kShadowFilter*: the directional filter, or PCF2x2 for a "hard" light
    float pcssTanRadius;  // a "pcss" light: tan of the sun's angular radius (shadowLightSize / 2); else 0
    float reserved;
    vec4 wsToLight;       // xyz = unit vector toward the light (opposite to the way it travels)
};
PENUMBRA_CHECK_SIZE(DirectionalShadowLight, 48)

struct DirectionalShadowData {
    // Tile t = lights[slot].firstTile + cascade: world -> (atlas uv, depth). Unused tiles are zero.
    mat4 atlasFromWorld[16];
    DirectionalCascade cascades[4];
    DirectionalShadowLight lights[4];
    // The distance fade ("Directional Shadows", Fading Shadows and Fading Cascades): the lit pass's
    // strength = saturate((1 - viewDepth / shadowDistance) * invDistanceFade) * light strength; in the
    // last cascade also * saturate((1 - distanceSqr * invRadiusSquared) * cascadeFadeScale).
    float invShadowDistance;
    float invDistanceFade;
    float cascadeFadeScale;  // 1 / (1 - (1 - cascadeFade)^2)
    float shadowDistance;    // maxDistance, or the camera's zFar when nearer (Max Distance)
    uint cascadeCount;
    uint filterMode;         // kShadowFilter*
    uint cascadeBlend;       // kCascadeBlend*
    uint lightCount;         // shadowed directional lights (0 = no directional shadows this frame)
    float atlasSize;         // in texels
    float invAtlasSize;
    float tileSize;          // in texels
    float invTileSize;
    uint biasMode;           // kShadowBias*
    uint fadeMode;           // kShadowFade*
    uint cascadeFit;         // kCascadeFit*
    uint reserved0;
    float invCascadeFade;    // the tight fit's blend band: the last cascadeFade of a slice's view depth
    float squaredFadeScale;  // scale and bias of the squared-distance fade (kShadowFadeSquared, shadow_fade.h)
    float squaredFadeBias;
    float reserved1;
};
PENUMBRA_CHECK_SIZE(DirectionalShadowData, 1424)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, cascades, 1024)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, lights, 1152)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, invShadowDistance, 1344)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, cascadeCount, 1360)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, atlasSize, 1376)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, biasMode, 1392)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, invCascadeFade, 1408)

PENUMBRA_GPU_NAMESPACE_END
#endif
