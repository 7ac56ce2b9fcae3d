#include "scene/texture_sampler.h"

#include <cmath>

namespace penumbra {

namespace {

constexpr int kNearest = 9728, kLinear = 9729;
constexpr int kNearestMipmapNearest = 9984, kLinearMipmapNearest = 9985;
constexpr int kNearestMipmapLinear = 9986, kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071, kMirroredRepeat = 33648, kRepeat = 10497;

// floor() of a texel coordinate, kept in int range (huge uvs wrap the same way in float as in int only
// up to 2^24 anyway).
int floorToInt(float x) { return int(std::floor(std::fmod(x, 16777216.0f))); }

}  // namespace

bool setGltfMagFilter(TextureSampler& sampler, int code) {
    if (code == -1) return true;
    if (code != kNearest && code != kLinear) return false;
    sampler.magFilter = code == kNearest ? TextureFilter::Nearest : TextureFilter::Linear;
    return true;
}

bool setGltfMinFilter(TextureSampler& sampler, int code) {
    switch (code) {
        case -1: return true;
        case kNearest: sampler.minFilter = TextureFilter::Nearest; sampler.mipmaps = MipmapMode::None; return true;
        case kLinear: sampler.minFilter = TextureFilter::Linear; sampler.mipmaps = MipmapMode::None; return true;
        case kNearestMipmapNearest: sampler.minFilter = TextureFilter::Nearest; sampler.mipmaps = MipmapMode::Nearest; return true;
        case kLinearMipmapNearest: sampler.minFilter = TextureFilter::Linear; sampler.mipmaps = MipmapMode::Nearest; return true;
        case kNearestMipmapLinear: sampler.minFilter = TextureFilter::Nearest; sampler.mipmaps = MipmapMode::Linear; return true;
        case kLinearMipmapLinear: sampler.minFilter = TextureFilter::Linear; sampler.mipmaps = MipmapMode::Linear; return true;
        default: return false;
    }
}

bool gltfWrap(int code, TextureWrap& wrap) {
    switch (code) {
        case -1: case kRepeat: wrap = TextureWrap::Repeat; return true;
        case kClampToEdge: wrap = TextureWrap::ClampToEdge; return true;
        case kMirroredRepeat: wrap = TextureWrap::MirroredRepeat; return true;
        default: return false;
    }
}

int gltfMagFilterCode(const TextureSampler& sampler) {
    return sampler.magFilter == TextureFilter::Nearest ? kNearest : kLinear;
}

int gltfMinFilterCode(const TextureSampler& sampler) {
    const bool nearest = sampler.minFilter == TextureFilter::Nearest;
    switch (sampler.mipmaps) {
        case MipmapMode::None: return nearest ? kNearest : kLinear;
        case MipmapMode::Nearest: return nearest ? kNearestMipmapNearest : kLinearMipmapNearest;
        case MipmapMode::Linear: return nearest ? kNearestMipmapLinear : kLinearMipmapLinear;
    }
    return kLinearMipmapLinear;
}

int gltfWrapCode(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::Repeat: return kRepeat;
        case TextureWrap::ClampToEdge: return kClampToEdge;
        case TextureWrap::MirroredRepeat: return kMirroredRepeat;
    }
    return kRepeat;
}

int wrapTexelIndex(int i, int size, TextureWrap wrap) {
    if (size <= 1) return 0;
    switch (wrap) {
        case TextureWrap::ClampToEdge: return i < 0 ? 0 : (i >= size ? size - 1 : i);
        case TextureWrap::MirroredRepeat: {
            int t = i % (2 * size);
            if (t < 0) t += 2 * size;
            return t < size ? t : 2 * size - 1 - t;
        }
        case TextureWrap::Repeat: break;
    }
    const int m = i % size;
    return m < 0 ? m + size : m;
}

TexelFootprint texelFootprint(glm::vec2 uv, uint32_t width, uint32_t height, TextureFilter filter,
                              const TextureSampler& sampler) {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    const glm::vec2 size{float(width), float(height)};
    TexelFootprint f;
    glm::ivec2 first;
    if (filter == TextureFilter::Nearest) {
        first = {floorToInt(uv.x * size.x), floorToInt(uv.y * size.y)};
        f.texel0 = {wrapTexelIndex(first.x, int(width), sampler.wrapS), wrapTexelIndex(first.y, int(height), sampler.wrapT)};
        f.texel1 = f.texel0;
        return f;
    }
    const glm::vec2 t = uv * size - 0.5f;  // texel centres sit at half-integers
    first = {floorToInt(t.x), floorToInt(t.y)};
    f.weight1 = t - glm::floor(t);
    f.texel0 = {wrapTexelIndex(first.x, int(width), sampler.wrapS), wrapTexelIndex(first.y, int(height), sampler.wrapT)};
    f.texel1 = {wrapTexelIndex(first.x + 1, int(width), sampler.wrapS),
                wrapTexelIndex(first.y + 1, int(height), sampler.wrapT)};
    return f;
}

float sampleTextureChannel(const Image& image, const TextureSampler& sampler, glm::vec2 uv, uint32_t channel) {
    const TexelFootprint f = texelFootprint(uv, image.width, image.height, sampler.magFilter, sampler);
    auto texel = [&](int x, int y) { return float(image.at(uint32_t(x), uint32_t(y), channel)) / 255.0f; };
    const float top = (1.0f - f.weight1.x) * texel(f.texel0.x, f.texel0.y) + f.weight1.x * texel(f.texel1.x, f.texel0.y);
    const float bottom = (1.0f - f.weight1.x) * texel(f.texel0.x, f.texel1.y) + f.weight1.x * texel(f.texel1.x, f.texel1.y);
    return (1.0f - f.weight1.y) * top + f.weight1.y * bottom;
}

}  // namespace penumbra
