#pragma once
// The tent filters behind PCF3x3 / PCF5x5 / PCF7x7 (Unity's ShadowSamplingTent.hlsl,
// SampleShadow_ComputeSamples_Tent_*): a tent (triangle) of radius 1.5 / 2.5 / 3.5 texels around the sample
// point, integrated over each shadow-map texel, then grouped into 2x2 blocks that one hardware-PCF (bilinear
// compare) fetch each evaluates: 4 / 9 / 16 fetches. penumbra/shadows/tent.glsl holds the same math for the
// GPU; this is its tested reference.
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/shadow_settings.h"

namespace penumbra {

struct TentTap {
    glm::vec2 texelOffset{0.0f};  // fetch position minus sample position, in texels
    float weight = 0.0f;
};

// Tent radius in texels: 0.5 for PCF2x2 (the single bilinear tap), else filterSize + 0.5.
float tentRadius(ShadowFilter filter);

// Weights of the texels first .. first+count-1 (texel j spans [j, j+1], centre j + 0.5) under the
// normalized 1D tent of `radius` centred at u (texel units): the tent's integral over each texel.
std::vector<float> tentTexelWeights1D(float u, float radius, int first, int count);

// The bilinear-PCF fetches of `filter` at `texelPosition` (texel units, texel (i, j) centred at
// (i + 0.5, j + 0.5)). PCF2x2: one tap at offset 0. The fetch grid is centred on the texel corner
// nearest the sample; weights sum to 1.
std::vector<TentTap> tentFilterTaps(ShadowFilter filter, glm::vec2 texelPosition);

}  // namespace penumbra
