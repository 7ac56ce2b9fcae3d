// Shadow sampling for the lit pass and the screen-space resolve (seed 000 §2-§4, seed 004):
// cascade selection by culling sphere, distance and cascade fades, normal bias, PCF / tent filters,
// cascade blending. Every function says which seed section it implements.
#ifndef PENUMBRA_SHADOWS_GLSL
#define PENUMBRA_SHADOWS_GLSL
#include "shadow_structs.h"
#include "shadow_tent.glsl"

layout(set = 0, binding = 5, std140) uniform DirectionalShadowBlock { DirectionalShadowData directionalShadows; };
layout(set = 0, binding = 6) uniform sampler2DShadow directionalShadowAtlas;

const uint kNoShadowSlot = 0xffffffffu;

struct ShadowSample {
    float attenuation;  // 1 = lit, 0 = fully shadowed (strength and fades applied)
    int cascade;        // cascade index sampled, -1 = none
};

// seed 000 §3.7 FadedShadowStrength: saturate((1 - distance * scale) * fade).
float fadedShadowStrength(float distance, float scale, float fade) {
    return clamp((1.0 - distance * scale) * fade, 0.0, 1.0);
}

// seed 000 §4.7 FilterDirectionalShadow: one hardware 2x2 PCF tap or a tent of taps (shadow_tent.glsl).
float filterDirectionalShadow(vec3 atlasUvDepth) {
    return sampleShadowFiltered(directionalShadowAtlas, atlasUvDepth, directionalShadows.atlasSize.yyxx,
                                directionalShadows.config.y);
}

// seed 000 §4.3 / §4.6: sample one cascade of a light, the surface pushed along its normal by the
// cascade's filter-texel diagonal times the light's normal bias.
float sampleDirectionalCascade(uint slot, int cascade, vec3 wsPosition, vec3 wsNormal) {
    vec4 light = directionalShadows.lights[slot];
    vec3 wsBiased = wsPosition + wsNormal * (light.z * directionalShadows.cascadeData[cascade].y);
    uint tile = uint(light.y) + uint(cascade);
    vec3 atlasUvDepth = (directionalShadows.atlasFromWorld[tile] * vec4(wsBiased, 1.0)).xyz;
    return filterDirectionalShadow(atlasUvDepth);
}

// seed 000 §3.5-§3.8 and §4.8 GetShadowData + GetDirectionalShadowAttenuation: choose the cascade by
// culling sphere, fade by distance and in the last cascade, blend cascades (soft: lerp two samples;
// dither: pick one by interleaved gradient noise), then lerp(1, shadow, strength).
ShadowSample directionalShadow(uint shadowSlot, vec3 wsPosition, vec3 wsNormal, vec2 pixel) {
    if (shadowSlot == kNoShadowSlot || shadowSlot >= directionalShadows.config.w) return ShadowSample(1.0, -1);
    int cascadeCount = int(directionalShadows.config.x);
    float viewDepth = -(frame.viewFromWorld * vec4(wsPosition, 1.0)).z;
    vec4 fade = directionalShadows.fade;
    float strength = fadedShadowStrength(viewDepth, fade.x, fade.y);
    float cascadeBlend = 1.0;
    int cascade = 0;
    for (; cascade < cascadeCount; ++cascade) {
        vec4 sphere = directionalShadows.cullingSpheres[cascade];
        vec3 offset = wsPosition - sphere.xyz;
        float distanceSquared = dot(offset, offset);
        if (distanceSquared < sphere.w) {
            float cascadeFade = fadedShadowStrength(distanceSquared, directionalShadows.cascadeData[cascade].x, fade.z);
            if (cascade == cascadeCount - 1) strength *= cascadeFade;
            else cascadeBlend = cascadeFade;
            break;
        }
    }
    if (cascade == cascadeCount) return ShadowSample(1.0, -1);  // beyond the last cascade: no shadow
    uint blendMode = directionalShadows.config.z;
    if (blendMode == kCascadeBlendDither && cascadeBlend < interleavedGradientNoise(pixel)) cascade += 1;
    if (blendMode != kCascadeBlendSoft) cascadeBlend = 1.0;

    strength *= directionalShadows.lights[shadowSlot].x;
    if (strength <= 0.0) return ShadowSample(1.0, cascade);
    float shadow = sampleDirectionalCascade(shadowSlot, cascade, wsPosition, wsNormal);
    if (cascadeBlend < 1.0)
        shadow = mix(sampleDirectionalCascade(shadowSlot, cascade + 1, wsPosition, wsNormal), shadow, cascadeBlend);
    return ShadowSample(mix(1.0, shadow, strength), cascade);
}

ShadowSample otherShadow(uint shadowSlot, vec3 wsPosition, vec3 wsNormal, vec3 wsToLight) {
    return ShadowSample(1.0, -1);
}
#endif
