#pragma once
// Alpha coverage of a material at a surface point, as the ray-traced reference sees it: the base
// colour alpha (texture alpha × factor alpha) and the per-hit dither value used for dithered shadows.
#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// Base colour alpha at `uv`: level 0 of the base colour texture with its sampler's magnification filter
// and wrap modes (scene/texture_sampler.h, the rule the GPU's sampler follows), times the factor's alpha.
// Level 0, not a mip level: the material's alpha as a function over the surface is the truth; mipmaps
// are the rasterizer's approximation of it. Alpha is linear in glTF (sRGB encodes only RGB).
float baseColorAlpha(const Material& material, const Texture* texture, glm::vec2 uv);

// A deterministic value in [0, 1) from a world-space position: the reference's replacement for the
// rasterizer's screen-space dither (interleaved gradient noise). Occlude when ditherValue(p) < alpha, so a
// surface of alpha a blocks a fraction a of the shadow rays that reach it.
float ditherValue(const glm::vec3& wsPosition);

}  // namespace penumbra
