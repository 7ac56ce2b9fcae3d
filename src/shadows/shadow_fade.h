#pragma once
// CPU mirror of the lit pass's cascade selection and fades (seed 000 §3.4-§3.8, §4.7), evaluated on a
// packed DirectionalShadowData: the reference the shaders must match, and what the tests check.
#include <cstdint>

#include <glm/glm.hpp>

#include "shadow_structs.h"

namespace penumbra {

// saturate((1 - distance * scale) * fade) (seed 000 §3.7 FadedShadowStrength).
float fadedShadowStrength(float distance, float scale, float fade);

struct CascadeSelection {
    uint32_t cascadeIndex = 0;  // == cascade count when outside every sphere
    float strength = 1.0f;      // distance fade x last-cascade fade (0 outside every sphere)
    float cascadeBlend = 1.0f;  // < 1 inside a non-last cascade's fade band (soft blend weight)
};

// GetShadowData of seed 000 §4.7 (before the hard/dither keyword handling): the first culling sphere
// containing wsPosition, the distance fade from the view depth and the cascade fade; no blend (1) where
// the next cascade's sphere does not hold the point.
CascadeSelection selectCascade(const gpu_data::DirectionalShadowData& data, const glm::vec3& wsPosition,
                               float viewDepth);

}  // namespace penumbra
