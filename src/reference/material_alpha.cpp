#include "reference/material_alpha.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace penumbra {
namespace {

int wrapRepeat(int i, int size) {
    const int m = i % size;
    return m < 0 ? m + size : m;
}

float texelAlpha(const Image& rgba, int x, int y) {
    const int w = int(rgba.width);
    const int h = int(rgba.height);
    return float(rgba.at(uint32_t(wrapRepeat(x, w)), uint32_t(wrapRepeat(y, h)), 3)) / 255.0f;
}

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
    float alpha = material.baseColorFactor.a;
    if (texture == nullptr || texture->rgba.empty() || texture->rgba.channels != 4) return alpha;
    // Texel centres sit at half-integers: the same addressing as a GPU's linear filter.
    const float x = uv.x * float(texture->rgba.width) - 0.5f;
    const float y = uv.y * float(texture->rgba.height) - 0.5f;
    if (!std::isfinite(x) || !std::isfinite(y)) return alpha;
    const float x0f = std::floor(x);
    const float y0f = std::floor(y);
    const float fx = x - x0f;
    const float fy = y - y0f;
    // Keep the integer texel index small before wrapping, so huge uvs can't overflow an int.
    const int x0 = int(std::fmod(x0f, float(texture->rgba.width)));
    const int y0 = int(std::fmod(y0f, float(texture->rgba.height)));
    const Image& img = texture->rgba;
    const float top = (1.0f - fx) * texelAlpha(img, x0, y0) + fx * texelAlpha(img, x0 + 1, y0);
    const float bottom = (1.0f - fx) * texelAlpha(img, x0, y0 + 1) + fx * texelAlpha(img, x0 + 1, y0 + 1);
    return alpha * ((1.0f - fy) * top + fy * bottom);
}

float ditherValue(const glm::vec3& wsPosition) {
    uint32_t h = mix(floatBits(wsPosition.x) ^ 0x9e3779b9U);
    h = mix(h ^ floatBits(wsPosition.y));
    h = mix(h ^ floatBits(wsPosition.z));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace penumbra
