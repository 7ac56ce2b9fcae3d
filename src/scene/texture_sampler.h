#pragma once
// How a texture is sampled: glTF's sampler (magFilter, minFilter, wrapS, wrapT), and the one texel rule
// every path applies to it. The GPU applies it in hardware (render/gpu_scene.cpp turns a TextureSampler
// into the Vulkan sampler of the texture table, used by the main view and the shadow casters alike);
// the ray-traced reference applies it here on the CPU (reference/material_alpha.cpp).
//
// The rule (Vulkan's "texel coordinate" rules, which glTF defers to): with size texels over [0, 1],
// NEAREST takes texel floor(u * size); LINEAR blends texels floor(u * size - 0.5) and the next one with
// weight fract(u * size - 0.5). The wrap mode then maps each integer texel index into [0, size).
#include <cstdint>

#include <glm/glm.hpp>

#include "penumbra/image.h"
#include "penumbra/scene.h"

namespace penumbra {

// glTF's enum values (9728 NEAREST ... 9987 LINEAR_MIPMAP_LINEAR, 33071 CLAMP_TO_EDGE, 33648
// MIRRORED_REPEAT, 10497 REPEAT). -1 = undefined (the default). False for any other value.
bool setGltfMagFilter(TextureSampler& sampler, int code);
bool setGltfMinFilter(TextureSampler& sampler, int code);
bool gltfWrap(int code, TextureWrap& wrap);
int gltfMagFilterCode(const TextureSampler& sampler);
int gltfMinFilterCode(const TextureSampler& sampler);
int gltfWrapCode(TextureWrap wrap);

// The integer texel index `i` of a texture `size` texels wide, wrapped into [0, size).
int wrapTexelIndex(int i, int size, TextureWrap wrap);

// The texels a sample at uv reads with `filter`, their blend weights along x and y (the rule above).
struct TexelFootprint {
    glm::ivec2 texel0{0};  // wrapped
    glm::ivec2 texel1{0};  // wrapped; = texel0 for NEAREST
    glm::vec2 weight1{0.0f};  // weight of texel1 (0 for NEAREST)
};
TexelFootprint texelFootprint(glm::vec2 uv, uint32_t width, uint32_t height, TextureFilter filter,
                              const TextureSampler& sampler);

// Channel `channel` of an 8-bit image at uv, level 0, with the sampler's magnification filter (the
// texture as a continuous function over the surface), in [0, 1]. Non-finite uv gives texel (0, 0).
float sampleTextureChannel(const Image& image, const TextureSampler& sampler, glm::vec2 uv, uint32_t channel);

}  // namespace penumbra
