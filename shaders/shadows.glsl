// Shadow sampling for the lit pass: cascade selection, fades, biases and filters (seed 000 §2-§4).
// Filled in by the directional- and spot-shadow work; until a light is reserved a shadow slot, its
// attenuation is 1 (fully lit).
#ifndef PENUMBRA_SHADOWS_GLSL
#define PENUMBRA_SHADOWS_GLSL

struct ShadowSample {
    float attenuation;  // 1 = lit, 0 = fully shadowed (strength and fades applied)
    int cascade;        // cascade index sampled, -1 = none
};

ShadowSample directionalShadow(uint shadowSlot, vec3 wsPosition, vec3 wsNormal, vec2 pixel) {
    return ShadowSample(1.0, -1);
}

ShadowSample otherShadow(uint shadowSlot, vec3 wsPosition, vec3 wsNormal, vec3 wsToLight) {
    return ShadowSample(1.0, -1);
}
#endif
