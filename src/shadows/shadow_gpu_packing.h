#pragma once
// Fills the std140/std430 block of the lit pass from a directional plan (seed 000 §2.2, §3.3, §3.7,
// §3.8, §4.2, §4.3, §4.6).
#include "shadow_structs.h"
#include "shadows/cascades.h"
#include "penumbra/shadow_settings.h"

namespace penumbra {

struct DirectionalShadowPlan;

// One unit of a directional light's shadowNormalBias, in shadow texels of the cascade (before the
// sqrt(2) of the texel diagonal): 1 + filterSize / 2 = 1 / 1.5 / 2 / 2.5 for PCF2x2 / 3x3 / 5x5 / 7x7.
// Seed 000 §4.6 uses filterSize + 1 (1 / 2 / 3 / 4); see packCascade for why and by how much we depart.
float directionalNormalBiasTexels(ShadowFilter filter);

// Seed 000 §4.6 SetCascadeData: texel = 2r / tileSize; filterSize = texel * (filter + 1);
// sphere w = (r - filterSize)^2; cascadeData = (1 / w, texel * directionalNormalBiasTexels * sqrt(2),
// texel, 0): the sphere still shrinks by the full filter footprint, the normal-bias unit is smaller.
void packCascade(const CascadeSphere& sphere, uint32_t tileSize, ShadowFilter filter, glm::vec4& cullingSphere,
                 glm::vec4& cascadeData);

// Everything of DirectionalShadowData from the plan's lights, cascades and tiles and the settings.
gpu_data::DirectionalShadowData packDirectionalShadowData(const DirectionalShadowPlan& plan,
                                                          const ShadowSettings& settings, float shadowDistance);

}  // namespace penumbra
