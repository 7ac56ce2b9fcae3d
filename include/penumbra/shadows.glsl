// <penumbra/shadows.glsl>: Penumbra's shadow sampling, one source for Penumbra's own lit pass,
// screen-space resolve and visibility resolve and for an engine's shaders. After Catlike Coding's Custom
// SRP tutorials "Directional Shadows" (sections Sampling Shadows, Cascaded Shadow Maps, Shadow Quality)
// and "Spotlight Shadows", and Unity URP's Shadows.hlsl: cascade selection by culling sphere, distance
// and cascade fades, normal or receiver-plane bias, PCF / tent filters, PCSS, cascade blending; and the
// virtual shadow maps' page-table lookups. Every function names the tutorial section or the Unity
// function it follows.
//
// An engine's fragment or compute shader (GL_GOOGLE_include_directive; compile with -I <prefix>/include):
//
//     #define PENUMBRA_SHADOW_SET 2           // optional: the descriptor set (default 0)
//     #define PENUMBRA_SHADOW_BINDING_BASE 0  // optional: added to every binding (default 0)
//     #include <penumbra/shadows.glsl>
//     ...
//     float shadow = penumbraShadow(light, wsPosition, wsNormal, gl_FragCoord.xy);  // 1 lit, 0 shadowed
//
// The descriptors it reads are <penumbra/shadows/bindings.h>'s (kShadowDescriptors in C++). Optional:
// PENUMBRA_SHADOW_CONSTANT_ID N makes the spot/point sampling's shadow kinds and filter specialization
// constants N and N + 1 (other_shadow_structs.h) and the directional sampling's kinds and filter
// constants N + 2 and N + 3 (kDirectionalShadows* and kShadowFilter* of shadow_structs.h); without it
// every kind is compiled and the filters are read from the data (ShadowFrameBindings::specialization
// gives a frame's values). Names this file declares: the penumbra* functions, the blocks and samplers
// of bindings.h, and the structs and k* constants of the headers in penumbra/shadows/.
#ifndef PENUMBRA_SHADOWS_GLSL
#define PENUMBRA_SHADOWS_GLSL
#ifndef PENUMBRA_SHADOW_SET
#define PENUMBRA_SHADOW_SET 0
#endif
#ifndef PENUMBRA_SHADOW_BINDING_BASE
#define PENUMBRA_SHADOW_BINDING_BASE 0
#endif
#include "shadows/bindings.h"
#include "shadows/structs.glsl"
#include "shadows/noise.glsl"
#include "shadows/bias.glsl"
#include "shadows/pcss.glsl"
#include "shadows/tent.glsl"
#include "shadows/virtual_face_shadows.glsl"
#include "shadows/virtual_shadows.glsl"

#define PENUMBRA_SHADOW_BINDING(name) set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + name
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingView), std140) uniform PenumbraShadowViewBlock { ShadowViewData shadowView; };
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingLights), std430) readonly buffer PenumbraShadowLightBlock {
    ShadowLightSlot shadowLights[];
};
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingDirectional), std140) uniform DirectionalShadowBlock {
    DirectionalShadowData directionalShadows;
};
// The atlases hold raw depth (R32F, nearest): the filters gather texels and compare (shadows/tent.glsl).
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingDirectionalAtlas)) uniform sampler2D directionalShadowAtlas;

#ifdef PENUMBRA_SHADOW_CONSTANT_ID
layout(constant_id = PENUMBRA_SHADOW_CONSTANT_ID + 2) const uint kDirectionalShadowMode = kDirectionalShadowsAll;
layout(constant_id = PENUMBRA_SHADOW_CONSTANT_ID + 3) const uint kDirectionalShadowFilter = kShadowFilterFromData;
#else
const uint kDirectionalShadowMode = kDirectionalShadowsAll;
const uint kDirectionalShadowFilter = kShadowFilterFromData;
#endif
// A directional light's filter: the specialized one where every reserved light has it, else its own.
uint directionalFilterMode(DirectionalShadowLight light) {
    return kDirectionalShadowFilter == kShadowFilterFromData ? light.filterMode : kDirectionalShadowFilter;
}
const bool kDirectionalCascadesCompiled = (kDirectionalShadowMode & kDirectionalShadowsCascades) != 0u;
const bool kDirectionalVirtualCompiled = (kDirectionalShadowMode & kDirectionalShadowsVirtual) != 0u;
const bool kDirectionalPcssCompiled = (kDirectionalShadowMode & kDirectionalShadowsPcss) != 0u;

struct ShadowSample {
    float attenuation;  // 1 = lit, 0 = fully shadowed (strength and fades applied)
    int cascade;        // cascade index sampled, -1 = none
};

// (1 / size, 1 / size, size, size) of a square atlas: the texelSize of the tent filters (tent.glsl).
vec4 shadowTexelSize(float atlasSize, float invAtlasSize) { return vec4(invAtlasSize, invAtlasSize, atlasSize, atlasSize); }

// FadedShadowStrength ("Directional Shadows", Fading Shadows): saturate((1 - distance * scale) * fade).
float fadedShadowStrength(float distance, float scale, float fade) {
    return clamp((1.0 - distance * scale) * fade, 0.0, 1.0);
}

// The uv rectangle of directional tile `tile` less one texel: where filter taps may read (tiles in rows
// of `split`, as "Directional Shadows", Multiple Lights lays them out).
vec4 directionalTileBounds(uint tile) {
    float tileSize = directionalShadows.tileSize, atlasSize = directionalShadows.atlasSize;
    uint split = uint(atlasSize / tileSize + 0.5);
    vec2 origin = vec2(float(tile % split), float(tile / split)) * tileSize;
    return vec4(origin + 1.0, origin + tileSize - 1.0) / atlasSize;
}

// "Directional Shadows", Normal Bias and PCF Filtering: sample one cascade of a light, biased as
// shadows.bias says (bias.glsl), with the light's filter: one bilinear 2x2 PCF tap or a tent
// (tent.glsl).
float sampleDirectionalCascade(uint slot, int cascade, ShadowReceiver receiver) {
    DirectionalShadowLight light = directionalShadows.lights[slot];
    uint filterMode = directionalFilterMode(light);
    uint tile = light.firstTile + uint(cascade);
    mat4 atlasFromWorld = directionalShadows.atlasFromWorld[tile];
    // The tile's world texel: 1 / (atlas texels per metre along u), exact for sphere and tight tiles.
    float wsTexel = 1.0 / (directionalShadows.atlasSize * length(vec3(atlasFromWorld[0][0], atlasFromWorld[1][0],
                                                                      atlasFromWorld[2][0])));
    ShadowBiasParams bias = ShadowBiasParams(directionalShadows.biasMode, light.normalBias, light.slopeBias, wsTexel,
                                             normalOffsetFootprint(filterMode), 0.0);
    vec3 wsToLight = light.wsToLight.xyz;
    vec3 wsLookup = biasedLookupPosition(receiver, wsToLight, bias);
    ShadowLookup lookup = shadowLookup(atlasFromWorld, receiver, wsLookup, wsToLight, bias, directionalShadows.atlasSize);
    vec4 texelSize = shadowTexelSize(directionalShadows.atlasSize, directionalShadows.invAtlasSize);
    if (kDirectionalPcssCompiled && light.pcssTanRadius > 0.0) {  // pcss: the depth range in metres is 1 / |d depth / d world|
        float metresPerDepth = 1.0 / length(vec3(atlasFromWorld[0][2], atlasFromWorld[1][2], atlasFromWorld[2][2]));
        PcssLight pcss = PcssLight(0.0, vec4(metresPerDepth, light.pcssTanRadius, wsTexel, 0.0));
        return pcssShadow(directionalShadowAtlas, lookup.uvDepth, lookup.depthGradient, texelSize,
                          directionalTileBounds(tile), pcss);
    }
    return sampleShadowFiltered(directionalShadowAtlas, lookup.uvDepth,
                                texelSize, filterMode, lookup.depthGradient, lookup.perTexelPlane);
}

bool insideCullingSphere(int cascade, vec3 wsPosition) {
    vec4 sphere = directionalShadows.cascades[cascade].cullingSphere;
    vec3 offset = wsPosition - sphere.xyz;
    return dot(offset, offset) < sphere.w;
}

struct CascadeChoice {
    int cascade;  // -1: beyond the last cascade
    float fade;   // 1 inside the cascade, falling to 0 over its blend band ("Fading Cascades")
};

// "Directional Shadows", Sampling Cascades and Fading Cascades: the first culling sphere that holds the
// point, faded over the sphere's outer band (squared distances); or, for tight cascades, the first slice
// whose split lies beyond the point's view depth, faded over the slice's last cascadeFade of view depth
// (the last slice: over the last cascadeFade of the shadow distance, where its sphere would end).
CascadeChoice selectDirectionalCascade(vec3 wsPosition, float viewDepth) {
    int cascadeCount = int(directionalShadows.cascadeCount);
    bool tight = directionalShadows.cascadeFit == kCascadeFitTight;
    for (int cascade = 0; cascade < cascadeCount; ++cascade) {
        DirectionalCascade data = directionalShadows.cascades[cascade];
        if (tight) {  // the last one fades toward the shadow distance, not its own end (shadow_fade.cpp)
            float scale = cascade + 1 == cascadeCount ? directionalShadows.invShadowDistance : 1.0 / data.vsSplit;
            if (viewDepth < data.vsSplit)
                return CascadeChoice(cascade, fadedShadowStrength(viewDepth, scale, directionalShadows.invCascadeFade));
            continue;
        }
        vec3 offset = wsPosition - data.cullingSphere.xyz;
        float distanceSquared = dot(offset, offset);
        if (distanceSquared < data.cullingSphere.w)
            return CascadeChoice(cascade, fadedShadowStrength(distanceSquared, data.invRadiusSquared, directionalShadows.cascadeFadeScale));
    }
    return CascadeChoice(-1, 0.0);
}

// The distance fade of every shadow (the fields of DirectionalShadowData or OtherShadowData): by view
// depth ("Directional Shadows", Fading Shadows; kShadowFadeLinear), or URP's GetMainLightShadowFade
// (_MainLightShadowParams.zw) by the squared distance to the camera, saturate(d^2 * scale + bias)
// fading the shadow out (kShadowFadeSquared).
struct DistanceFade {
    uint mode;  // kShadowFade*
    float invShadowDistance;
    float invDistanceFade;
    float squaredScale;
    float squaredBias;
};

float distanceFadeStrength(vec3 wsPosition, float viewDepth, DistanceFade fade) {
    if (fade.mode == kShadowFadeSquared) {
        vec3 fromCamera = wsPosition - shadowView.wsCameraPosition.xyz;
        return 1.0 - clamp(dot(fromCamera, fromCamera) * fade.squaredScale + fade.squaredBias, 0.0, 1.0);
    }
    return fadedShadowStrength(viewDepth, fade.invShadowDistance, fade.invDistanceFade);
}

// GetShadowData + GetDirectionalShadowAttenuation ("Directional Shadows", Culling Shadow Sampling to
// Fading Cascades, Blending Cascades, Dithered Transition): choose the cascade by culling sphere, fade by
// distance and in the last cascade, blend cascades (soft: lerp two samples; dither: pick one by
// interleaved gradient noise), then lerp(1, shadow, strength).
ShadowSample directionalShadow(uint shadowSlot, ShadowReceiver receiver, vec2 pixel) {
    if (kDirectionalShadowMode == 0u || shadowSlot == kNoShadowSlot || shadowSlot >= directionalShadows.lightCount)
        return ShadowSample(1.0, -1);
    vec3 wsPosition = receiver.wsPosition;
    float viewDepth = -(shadowView.viewFromWorld * vec4(wsPosition, 1.0)).z;
    DistanceFade fade = DistanceFade(directionalShadows.fadeMode, directionalShadows.invShadowDistance,
                                     directionalShadows.invDistanceFade, directionalShadows.squaredFadeScale,
                                     directionalShadows.squaredFadeBias);
    float strength = distanceFadeStrength(wsPosition, viewDepth, fade);
    if (kDirectionalVirtualCompiled && virtualShadows.enabled != 0u) {  // mode = virtual: the light's virtual map, no cascades
        DirectionalShadowLight light = directionalShadows.lights[shadowSlot];
        strength *= light.strength;
        if (strength <= 0.0) return ShadowSample(1.0, -1);
        int level;
        float shadow = sampleDirectionalVirtual(shadowSlot, light, directionalShadows.biasMode, receiver, viewDepth,
                                                directionalFilterMode(light), kDirectionalPcssCompiled, level);
        return ShadowSample(mix(1.0, shadow, strength), level);  // --aov cascades shows the level
    }
    if (!kDirectionalCascadesCompiled) return ShadowSample(1.0, -1);
    CascadeChoice choice = selectDirectionalCascade(wsPosition, viewDepth);
    if (choice.cascade < 0) return ShadowSample(1.0, -1);  // beyond the last cascade: no shadow
    int cascade = choice.cascade;
    float cascadeBlend = 1.0;
    if (cascade == int(directionalShadows.cascadeCount) - 1) strength *= choice.fade;
    else cascadeBlend = choice.fade;
    // Blend only toward a cascade that holds the point: culling spheres need not nest, and next to the
    // camera a point in cascade i's band can lie outside sphere i + 1 (its tile never saw it). A tight
    // cascade's box holds the previous one's band by construction.
    if (cascadeBlend < 1.0 && directionalShadows.cascadeFit == kCascadeFitSphere && !insideCullingSphere(cascade + 1, wsPosition))
        cascadeBlend = 1.0;
    uint blendMode = directionalShadows.cascadeBlend;
    if (blendMode == kCascadeBlendDither && cascadeBlend < interleavedGradientNoise(pixel)) cascade += 1;
    if (blendMode != kCascadeBlendSoft) cascadeBlend = 1.0;

    strength *= directionalShadows.lights[shadowSlot].strength;
    if (strength <= 0.0) return ShadowSample(1.0, cascade);
    float shadow = sampleDirectionalCascade(shadowSlot, cascade, receiver);
    if (cascadeBlend < 1.0)
        shadow = mix(sampleDirectionalCascade(shadowSlot, cascade + 1, receiver), shadow, cascadeBlend);
    return ShadowSample(mix(1.0, shadow, strength), cascade);
}

// ---- Spot and point lights: the "other" atlas (Catlike Coding "Spotlight Shadows") ----

// Like the _SHADOWS_HARD / _SHADOWS_SOFT keywords of "Spotlight Shadows" (Shader Keywords), the renderer
// specializes the lit pass by the reserved lights' shadow kinds (kOtherShadowsHard | kOtherShadowsSoft bits;
// 0 = no spot/point shadows, otherShadow returns 1 at once; kOtherShadowsVirtual alone: the virtual faces'
// sampling only), and the soft filter, so a frame pays only for the sampling code it uses (and lavapipe
// compiles no more than that). The generic variant (every mode bit, filter kShadowFilterFromData) gives
// the same result for every frame; the renderer draws with it while the specialized one is still being built.
#ifdef PENUMBRA_SHADOW_CONSTANT_ID
layout(constant_id = PENUMBRA_SHADOW_CONSTANT_ID) const uint kOtherShadowMode = 0u;
layout(constant_id = PENUMBRA_SHADOW_CONSTANT_ID + 1) const uint kOtherShadowFilter = 2u;  // kShadowFilterPcf5x5
#else
const uint kOtherShadowMode = kOtherShadowsHard | kOtherShadowsSoft | kOtherShadowsVirtual;  // the generic variant
const uint kOtherShadowFilter = kShadowFilterFromData;
#endif
const bool kOtherShadowsFromFaces = (kOtherShadowMode & kOtherShadowsVirtual) != 0u;  // shadows.spot.mode = virtual
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingOther), std140) uniform OtherShadowBlock { OtherShadowData otherShadows; };
layout(PENUMBRA_SHADOW_BINDING(kShadowBindingOtherAtlas)) uniform sampler2D otherShadowAtlas;

// HardShadowAttenuation / SoftShadowAttenuation ("Spotlight Shadows", Soft Shadows), the soft one with
// spot.filter's tent.
float filterOtherShadow(ShadowLookup lookup, bool soft) {
    bool useSoft = kOtherShadowMode == kOtherShadowsSoft || (kOtherShadowMode != kOtherShadowsHard && soft);
    vec4 texelSize = shadowTexelSize(otherShadows.atlasSize, otherShadows.invAtlasSize);
    uint filterMode = kOtherShadowFilter == kShadowFilterFromData ? otherShadows.filterMode : kOtherShadowFilter;
    if (useSoft)
        return sampleShadowFiltered(otherShadowAtlas, lookup.uvDepth, texelSize, filterMode,
                                    lookup.depthGradient, lookup.perTexelPlane);
    return sampleShadowPcf2x2(otherShadowAtlas, lookup.uvDepth, texelSize, lookup.depthGradient,
                              lookup.perTexelPlane);
}

// Cube face (+X, -X, +Y, -Y, +Z, -Z order) holding a direction from a point light: its major axis.
uint pointLightFace(vec3 wsFromLight) {
    vec3 a = abs(wsFromLight);
    uint axis = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (wsFromLight[axis] < 0.0 ? 1u : 0u);
}

// ShadowAttenuation of "Spotlight Shadows", extended to point lights: bias the lookup as shadows.bias
// says (bias.glsl; the world texel grows with the distance along the tile's axis), pick the tile
// (a point light's cube face by the major axis of light -> lookup point), project, divide by w, keep the
// filter inside the tile's drawn interior (inside the scissored border, "Shadow Map Atlas"), compare,
// lerp by strength.
// Fragments behind a spot light or outside its tile's frustum are not shadowed.
ShadowSample otherShadow(uint shadowSlot, ShadowReceiver receiver, vec3 wsToLight) {
    if (kOtherShadowMode == 0u) return ShadowSample(1.0, -1);
    if (shadowSlot == kNoShadowSlot || shadowSlot >= otherShadows.lightCount) return ShadowSample(1.0, -1);
    OtherShadowLight light = otherShadows.lights[shadowSlot];
    float viewDepth = -(shadowView.viewFromWorld * vec4(receiver.wsPosition, 1.0)).z;
    DistanceFade fade = DistanceFade(otherShadows.fadeMode, otherShadows.invShadowDistance, otherShadows.invDistanceFade,
                                     otherShadows.squaredFadeScale, otherShadows.squaredFadeBias);
    float strength = light.strength * distanceFadeStrength(receiver.wsPosition, viewDepth, fade);
    if (strength <= 0.0) return ShadowSample(1.0, -1);

    vec3 wsFromLight = receiver.wsPosition - light.wsPosition.xyz;
    bool pointLight = light.point != 0u;
    float distance = pointLight ? max(max(abs(wsFromLight.x), abs(wsFromLight.y)), abs(wsFromLight.z))
                                : dot(wsFromLight, light.wsAxis.xyz);
    if (distance <= 0.0) return ShadowSample(1.0, -1);
    if (kOtherShadowsFromFaces && virtualFaces.enabled != 0u) {  // the light's virtual faces, no atlas tile
        int level;
        float shadow = sampleOtherVirtual(light, otherShadows.biasMode, receiver, wsToLight, viewDepth, level);
        return ShadowSample(mix(1.0, shadow, strength), -1);
    }
    if (kOtherShadowMode == kOtherShadowsVirtual) return ShadowSample(1.0, -1);  // the atlas is not compiled in
    bool soft = light.soft != 0u;
    ShadowBiasParams bias = ShadowBiasParams(otherShadows.biasMode, light.normalBias, light.slopeBias,
                                             light.wsTexelPerDistance * distance, normalOffsetFootprint(light.filterMode),
                                             light.depthBias);
    vec3 wsLookup = biasedLookupPosition(receiver, wsToLight, bias);
    uint tile = light.firstTile;
    if (pointLight) tile += pointLightFace(wsLookup - light.wsPosition.xyz);  // the face that holds the lookup point
    ShadowLookup lookup = shadowLookup(otherShadows.atlasFromWorld[tile], receiver, wsLookup, wsToLight, bias,
                                       otherShadows.atlasSize);
    if (lookup.w <= 0.0) return ShadowSample(1.0, -1);
    if (lookup.uvDepth.z >= 1.0) return ShadowSample(1.0, -1);  // beyond the far plane (range): no caster drawn there

    vec4 bounds = otherShadows.tileBounds[tile];
    // The cone (or a point light's 90° face) lies inside `bounds`, the drawn interior less the filter
    // reach: a fragment outside it gets no light from this tile, and clamping it onto the tile's edge
    // would smear edge texels into streaks across the AOV.
    if (any(lessThan(lookup.uvDepth.xy, bounds.xy)) || any(greaterThan(lookup.uvDepth.xy, bounds.zw)))
        return ShadowSample(1.0, -1);
    float shadow = light.pcssRadius > 0.0
        ? pcssShadow(otherShadowAtlas, lookup.uvDepth, lookup.depthGradient,
                     shadowTexelSize(otherShadows.atlasSize, otherShadows.invAtlasSize), bounds,
                     PcssLight(1.0, vec4(light.pcssRadius, light.nearDistance, light.farDistance, light.wsTexelPerDistance)))
        : filterOtherShadow(lookup, soft);
    return ShadowSample(mix(1.0, shadow, strength), -1);
}
// ---- The entry points of an engine's shaders ----

// Light `light`'s shadow term at a surface point, as Penumbra's lit pass computes it: 1 lit, 0 fully
// shadowed, the light's strength, the distance fade and the cascade blend applied. `light` indexes the
// light table (PenumbraShadowLightBlock, the caller's light order); wsNormal is the unit shading normal
// turned toward the viewer, wsGeometricNormal the triangle's unit normal on the same side (the
// receiver-plane and scaled-normal biases use it), pixel the window position of the pixel centre
// (dithered cascade blends). A light without shadows, or beyond the table, gives 1.
float penumbraShadowWithGeometricNormal(uint light, vec3 wsPosition, vec3 wsNormal, vec3 wsGeometricNormal, vec2 pixel) {
    if (light >= shadowView.lightCount) return 1.0;
    ShadowLightSlot entry = shadowLights[light];
    ShadowReceiver receiver = ShadowReceiver(wsPosition, wsNormal, wsGeometricNormal);
    if (entry.type == kLightDirectional) return directionalShadow(entry.slot, receiver, pixel).attenuation;
    if (entry.slot == kNoShadowSlot || entry.slot >= otherShadows.lightCount) return 1.0;
    vec3 wsOffset = otherShadows.lights[entry.slot].wsPosition.xyz - wsPosition;
    vec3 wsToLight = wsOffset * inversesqrt(max(dot(wsOffset, wsOffset), 1e-8));
    return otherShadow(entry.slot, receiver, wsToLight).attenuation;
}

// The same where only the shading normal is known (a G-buffer without the triangle's normal): it serves
// as the geometric normal too, exact on flat-shaded surfaces.
float penumbraShadow(uint light, vec3 wsPosition, vec3 wsNormal, vec2 pixel) {
    return penumbraShadowWithGeometricNormal(light, wsPosition, wsNormal, wsNormal, pixel);
}

#endif
