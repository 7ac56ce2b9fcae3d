#pragma once
// CPU mirror of the lit pass's cascade selection and fades (Catlike Coding "Directional Shadows", Sampling
// Cascades to Fading Cascades, Blending Cascades), evaluated on a packed DirectionalShadowData: the reference
// the shaders must match, and what the tests check.
#include <cstdint>

#include <glm/glm.hpp>

#include "shadow_structs.h"
#include "penumbra/shadow_settings.h"

namespace penumbra {

// saturate((1 - distance * scale) * fade) (FadedShadowStrength, "Directional Shadows", Fading Shadows).
float fadedShadowStrength(float distance, float scale, float fade);

// URP's squared-distance fade (_MainLightShadowParams.zw, ShadowUtils.GetScaleAndBiasForLinearDistanceFade):
// with start = shadowDistance (1 - distanceFade), fade = saturate(d^2 scale + bias) rises from 0 at start to
// 1 at the shadow distance, and the shadow's strength is 1 - fade.
glm::vec2 squaredFadeScaleBias(float shadowDistance, float distanceFade);

// The distance fade's strength at wsPosition (1 = full shadow): by view depth or by
// the squared distance to the camera (URP), as the shaders' distanceFadeStrength.
float distanceFadeStrength(ShadowFadeMode mode, float shadowDistance, float distanceFade, float viewDepth,
                           float cameraDistanceSquared);

struct CascadeSelection {
    uint32_t cascadeIndex = 0;  // == cascade count when outside every sphere
    float strength = 1.0f;      // distance fade x last-cascade fade (0 outside every sphere)
    float cascadeBlend = 1.0f;  // < 1 inside a non-last cascade's fade band (soft blend weight)
};

// GetShadowData of "Directional Shadows" (before the hard/dither keyword handling): the first culling sphere
// containing wsPosition (tight fit: the first slice whose split lies beyond viewDepth), the distance fade
// (the packed fade mode; wsCamera for the squared one) and the cascade fade; no blend (1) where the next
// cascade's sphere does not hold the point.
CascadeSelection selectCascade(const gpu_data::DirectionalShadowData& data, const glm::vec3& wsPosition,
                               float viewDepth, const glm::vec3& wsCamera = glm::vec3(0.0f));

}  // namespace penumbra
