// Direct lighting: Lambert diffuse + GGX specular (Smith-GGX correlated visibility, Schlick Fresnel),
// KHR_lights_punctual attenuation for spot and point lights. The display transform of the shaded
// radiance (toneMap) comes with it from tone_mapping.glsl.
#ifndef PENUMBRA_LIGHTING_GLSL
#define PENUMBRA_LIGHTING_GLSL
#include "tone_mapping.glsl"

const float kPi = 3.14159265358979;

struct Surface {
    vec3 wsPosition;
    vec3 wsNormal;
    vec3 wsToCamera;
    vec3 baseColor;
    float metallic;
    float roughness;
};

float ggxDistribution(float nDotH, float alpha) {
    float a2 = alpha * alpha;
    float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

float smithGgxVisibility(float nDotL, float nDotV, float alpha) {
    float a2 = alpha * alpha;
    float gv = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
    float gl = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-5);
}

// Outgoing radiance for unit irradiance from direction wsToLight (before N.L).
vec3 brdf(Surface s, vec3 wsToLight) {
    vec3 h = normalize(wsToLight + s.wsToCamera);
    float nDotL = max(dot(s.wsNormal, wsToLight), 0.0);
    float nDotV = max(dot(s.wsNormal, s.wsToCamera), 1e-4);
    float nDotH = max(dot(s.wsNormal, h), 0.0);
    float vDotH = max(dot(s.wsToCamera, h), 0.0);
    float alpha = max(s.roughness * s.roughness, 0.002);
    vec3 f0 = mix(vec3(0.04), s.baseColor, s.metallic);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
    vec3 specular = fresnel * ggxDistribution(nDotH, alpha) * smithGgxVisibility(nDotL, nDotV, alpha);
    vec3 diffuse = (1.0 - fresnel) * (1.0 - s.metallic) * s.baseColor / kPi;
    return diffuse + specular;
}

// KHR_lights_punctual range window and spot cone attenuation.
float rangeAttenuation(float distanceSquared, float inverseRangeSquared) {
    if (inverseRangeSquared <= 0.0) return 1.0 / max(distanceSquared, 1e-4);
    float ratio = distanceSquared * inverseRangeSquared;
    float window = clamp(1.0 - ratio * ratio, 0.0, 1.0);
    return window * window / max(distanceSquared, 1e-4);
}

float spotAttenuation(vec3 wsFromLight, vec3 wsSpotDirection, float spotScale, float spotOffset) {
    float cd = dot(wsSpotDirection, wsFromLight);
    float t = clamp(cd * spotScale + spotOffset, 0.0, 1.0);
    return t * t;
}
#endif
