#pragma once
// Fills the std140/std430 block of the lit pass from a directional plan (the shadow data of
// Catlike Coding "Directional Shadows": per light, per cascade, fades, biases, filter).
#include "shadow_structs.h"
#include "shadows/cascades.h"
#include "penumbra/shadow_settings.h"

namespace penumbra {

struct DirectionalShadowPlan;

// SetCascadeData of "Directional Shadows" (PCF Filtering): texel = 2r / tileSize; filterSize = texel *
// (filter + 1); sphere w = (r - filterSize)^2; invRadiusSquared = 1 / w, normalBiasUnit = texel *
// normalOffsetFootprint(filter), wsTexelSize = texel: the sphere still shrinks by the full filter footprint,
// the normal-bias unit is smaller.
// The texels a lit-pass lookup may reach beyond a receiver in its shadow map: the filter's taps (or the
// PCSS search radius, kPcssMaxRadiusTexels), the normal offset (normalBias units of
// normalOffsetFootprint) and a texel of rounding either side. The tight cascade fit keeps that much
// around the visible receivers; the virtual shadow maps' marking requests that much around each pixel.
float lookupReachTexels(float normalBias, bool pcss, ShadowFilter filter);

gpu_data::DirectionalCascade packCascade(const CascadeSphere& sphere, uint32_t tileSize, ShadowFilter filter);

// Everything of DirectionalShadowData from the plan's lights, cascades and tiles and the settings.
gpu_data::DirectionalShadowData packDirectionalShadowData(const DirectionalShadowPlan& plan,
                                                          const ShadowSettings& settings, float shadowDistance);

}  // namespace penumbra
