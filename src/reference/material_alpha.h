#pragma once
// Alpha coverage of a material at a surface point, as the ray-traced reference sees it: the base
// colour alpha (texture alpha × factor alpha) and the per-hit dither value used for dithered shadows.
#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// Base colour alpha at `uv`: level 0 of the base colour texture, bilinear, REPEAT wrap, times the
// factor's alpha. Alpha is linear in glTF (sRGB encodes only RGB), so no decoding is needed.
float baseColorAlpha(const Material& material, const Texture* texture, glm::vec2 uv);

// A deterministic value in [0, 1) from a world-space position: the reference's replacement for the
// rasterizer's screen-space dither (seed 000 §5.3). Occlude when ditherValue(p) < alpha, so a
// surface of alpha a blocks a fraction a of the shadow rays that reach it.
float ditherValue(const glm::vec3& wsPosition);

}  // namespace penumbra
