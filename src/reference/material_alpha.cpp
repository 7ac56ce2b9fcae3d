#include "scene/texture_sampler.h"
#include "reference/material_alpha.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace penumbra {
namespace {

uint32_t floatBits(float f) {
    if (f == 0.0f) f = 0.0f;  // -0 and +0 hash alike
    uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof(bits));
    return bits;
}

// A 32-bit integer mix (xorshift-multiply) with good avalanche; any fixed hash would do.
uint32_t mix(uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352dU;
    h ^= h >> 15;
    h *= 0x846ca68bU;
    h ^= h >> 16;
    return h;
}

}  // namespace

float baseColorAlpha(const Material& material, const Texture* texture, glm::vec2 uv) {
    const float alpha = material.baseColorFactor.a;
    if (texture == nullptr || texture->rgba.empty() || texture->rgba.channels != 4) return alpha;
    return alpha * sampleTextureChannel(texture->rgba, texture->sampler, uv, 3);
}

float ditherValue(const glm::vec3& wsPosition) {
    uint32_t h = mix(floatBits(wsPosition.x) ^ 0x9e3779b9U);
    h = mix(h ^ floatBits(wsPosition.y));
    h = mix(h ^ floatBits(wsPosition.z));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace penumbra
