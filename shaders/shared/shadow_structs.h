// GPU data of the directional shadows, shared by C++ (shadows/shadow_gpu_packing) and GLSL.
// Filled by penumbra::packDirectionalShadowData from a ShadowFrame; one uniform/storage block per frame.
//
// Conventions (one for the whole project's shadow maps):
// - Shadow-map clip space is Vulkan's: x right, y DOWN in NDC, z in [0, 1]. Light view space looks along
//   -Z with +Y up (like the camera), so light-space +Y lands at the top of a tile.
// - Standard depth: 0 at the near plane (closest to the light), 1 at the far plane. Clear to 1, render
//   casters with compare op LESS (or LESS_OR_EQUAL), sample with a sampler2DShadow whose compare op is
//   LESS_OR_EQUAL: "fragment depth <= stored depth -> lit (1)".
// - atlasFromWorld maps a world position (w = 1) straight to (atlas u, atlas v, depth, 1): u, v in [0, 1]
//   over the whole atlas with v = 0 at the top row (texel row 0); orthographic, so no divide by w needed.
#ifndef PENUMBRA_SHADOW_STRUCTS_H
#define PENUMBRA_SHADOW_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kMaxShadowedDirectionalLights, 4u)
PENUMBRA_CONST(uint, kMaxCascades, 4u)
PENUMBRA_CONST(uint, kMaxDirectionalShadowTiles, 16u)

// DirectionalShadowData.config.y mirrors ShadowFilter, .z mirrors CascadeBlend.
PENUMBRA_CONST(uint, kShadowFilterPcf2x2, 0u)
PENUMBRA_CONST(uint, kShadowFilterPcf3x3, 1u)
PENUMBRA_CONST(uint, kShadowFilterPcf5x5, 2u)
PENUMBRA_CONST(uint, kShadowFilterPcf7x7, 3u)
// Value of the lit pass's spot-filter specialization constant that reads the filter from
// OtherShadowData.config.y instead: the generic variant used while a specialized one is built.
PENUMBRA_CONST(uint, kShadowFilterFromData, 4u)
PENUMBRA_CONST(uint, kCascadeBlendHard, 0u)
PENUMBRA_CONST(uint, kCascadeBlendSoft, 1u)
PENUMBRA_CONST(uint, kCascadeBlendDither, 2u)

// ShadowBias.x of DirectionalShadowData and OtherShadowData mirrors ShadowBiasMode (shadows.bias):
// how the lit pass keeps a surface from shadowing itself (see shaders/shadows.glsl shadowLookup).
PENUMBRA_CONST(uint, kShadowBiasNormal, 0u)          // constant normal offset (the classic rule)
PENUMBRA_CONST(uint, kShadowBiasScaledNormal, 1u)    // normal offset x the texel's size x sin(N, L)
PENUMBRA_CONST(uint, kShadowBiasReceiverPlane, 2u)   // each fetch compares the receiver plane's depth there

// PCSS (shaders/shadow_pcss.glsl): the widest blocker search and filter radius, in texels; the tight fit
// keeps that many texels around the visible receivers of a pcss light.
PENUMBRA_CONST(float, kPcssMaxRadiusTexels, 24.0f)

// modes.z: how cascades were fitted and so how the lit pass selects one (shadows.directional.fit).
PENUMBRA_CONST(uint, kCascadeFitSphere, 0u)  // the first culling sphere that holds the point
PENUMBRA_CONST(uint, kCascadeFitTight, 1u)   // the first slice whose split lies beyond the point's view depth

// modes.y: the distance fade (shadows.fadeMode).
PENUMBRA_CONST(uint, kShadowFadeLinear, 0u)   // by view depth, over the last distanceFade
PENUMBRA_CONST(uint, kShadowFadeSquared, 1u)  // URP's: by squared camera distance, scale and bias

// One unit of a light's shadowNormalBias, in texels of its shadow map: the texel diagonal x (1 + filter
// / 2), for directional, spot and point lights alike (one rule; spot lights once used 1 + filter).
// filterMode = kShadowFilter* of the light (PCF2x2 for "hard" lights). Measured in shadow_gpu_packing.cpp.
PENUMBRA_INLINE float normalOffsetFootprint(uint filterMode) { return (1.0f + 0.5f * float(filterMode)) * 1.4142136f; }

struct DirectionalShadowData {
    // Tile t = lights[slot].y + cascade: world -> (atlas uv, depth). Unused tiles are zero.
    mat4 atlasFromWorld[16];
    // Per cascade (shared by all lights): xyz = world centre, w = (r - filterSize)^2, the radius shrunk
    // by the filter footprint so filtering stays inside the tile (as SetCascadeData of Catlike Coding
    // "Directional Shadows", PCF Filtering).
    vec4 cullingSpheres[4];
    // Per cascade: x = 1 / cullingSpheres.w, y = the world-space normal-bias unit,
    // z = world texel size (2r / tileSize), w = the view depth where the cascade's slice ends (its split).
    // One unit of shadowNormalBias ("shadow texels", docs/scene-format.md) = texel * (1 + filter / 2) *
    // sqrt(2): the texel diagonal (as in "Directional Shadows", Normal Bias) times 1 / 1.5 / 2 / 2.5 for
    // PCF2x2 / 3x3 / 5x5 / 7x7. The tutorial (PCF Filtering) scales by filter + 1 (1 / 2 / 3 / 4); measured,
    // that over-biases wide filters (thin_wall PCF7x7: 2.25 % misclassified, 0.28 % interior) while half a
    // texel per filter step already removes acne (1.47 % / 0.00 %); numbers in
    // src/shadows/shadow_gpu_packing.cpp.
    vec4 cascadeData[4];
    // Per shadowed light slot: x = strength, y = first tile index, z = normal bias (light's
    // shadowNormalBias, multiplies cascadeData.y), w = scene light index.
    vec4 lights[4];
    // x = 1 / shadow distance, y = 1 / distanceFade, z = 1 / (1 - (1 - cascadeFade)^2) ("Directional
    // Shadows", Fading Shadows and Fading Cascades), w = shadow distance: maxDistance, or the camera's zFar
    // when nearer (Max Distance). The
    // lit pass: strength = saturate((1 - viewDepth * x) * y) * light strength; in the last cascade also
    // * saturate((1 - distanceSqr * cascadeData.x) * z).
    vec4 fade;
    // x = cascade count, y = filter (kShadowFilter*), z = cascade blend (kCascadeBlend*),
    // w = shadowed directional light count (0 = no directional shadows this frame).
    uvec4 config;
    // x = atlas size in texels, y = 1 / atlas size, z = tile size in texels, w = 1 / tile size.
    // The tent filters take vec4(1/size, 1/size, size, size) = atlasSize.yyxx.
    vec4 atlasSize;
    // Per shadowed light slot: x = normal-bias multiplier (shadowNormalBias), y = slope-scale bias
    // (shadowBias: depth per texel of receiver slope, applied in the lit pass, not the rasterizer),
    // z = filter (kShadowFilter*: the directional filter, or PCF2x2 for a "hard" light), w = tan of the
    // sun's angular radius for a "pcss" light (its shadowLightSize / 2), 0 for every other.
    vec4 lightBias[4];
    // Per shadowed light slot: xyz = unit vector toward the light (opposite to the way it travels).
    vec4 lightDirections[4];
    // x = bias mode (kShadowBias*), y = fade mode (kShadowFade*), z = cascade fit (kCascadeFit*), w unused.
    uvec4 modes;
    // x = 1 / cascadeFade: the tight fit's blend band, the last cascadeFade of a slice's view depth;
    // y, z = scale and bias of the squared-distance fade (kShadowFadeSquared, shadow_fade.h); w unused.
    vec4 depthSelection;
};
PENUMBRA_CHECK_SIZE(DirectionalShadowData, 1424)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, cullingSpheres, 1024)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, cascadeData, 1088)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, lights, 1152)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, fade, 1216)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, config, 1232)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, atlasSize, 1248)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, lightBias, 1264)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, lightDirections, 1328)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, modes, 1392)
PENUMBRA_CHECK_LAYOUT(DirectionalShadowData, depthSelection, 1408)

PENUMBRA_GPU_NAMESPACE_END
#endif
