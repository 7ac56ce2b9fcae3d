#pragma once
// The scene on the GPU: one vertex storage buffer, one index buffer, the instance and material
// buffers and the base-colour texture table. Draws are recorded from DrawItems (one per Instance),
// which any pass (main view, shadow tiles, a future compute rasterizer) can filter.
#include <vector>

#include "gpu/device.h"
#include "scene/scene.h"

namespace penumbra {

struct DrawItem {
    uint32_t instanceIndex = 0;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t materialIndex = 0;
};

// The GPU sampler of a glTF texture sampler (filters, mipmap mode, wrap modes).
gpu::SamplerDesc samplerDesc(const TextureSampler& sampler);

class GpuScene {
public:
    GpuScene(gpu::Device& device, const Scene& scene);

    const std::vector<DrawItem>& draws() const { return draws_; }
    gpu::BufferHandle vertexBuffer() const { return vertices_; }
    gpu::BufferHandle indexBuffer() const { return indices_; }
    gpu::BufferHandle instanceBuffer() const { return instances_; }
    gpu::BufferHandle materialBuffer() const { return materials_; }
    gpu::TextureTableHandle textureTable() const { return textureTable_; }

private:
    std::vector<DrawItem> draws_;
    gpu::BufferHandle vertices_, indices_, instances_, materials_;
    gpu::TextureTableHandle textureTable_;
};

}  // namespace penumbra
