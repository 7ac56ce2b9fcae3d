#pragma once
// Copies what a shadow rasterizer drew into the sampled atlas: an R32F image that compute passes write
// and the lit pass reads with textureGather (penumbra/shadows/tent.glsl compares each texel itself). The
// compute rasterizer draws into a buffer of float bits, the hardware one into a D32 depth target; either
// way only the drawn tiles' rects are copied (cached tiles keep theirs), or the whole atlas when it is fresh.
// One thread per texel, one dispatch per rect.
#include <span>
#include <string_view>

#include "gpu/device.h"

namespace penumbra {

class AtlasCopyPass {
public:
    explicit AtlasCopyPass(gpu::Device& device);
    ~AtlasCopyPass();
    AtlasCopyPass(const AtlasCopyPass&) = delete;
    AtlasCopyPass& operator=(const AtlasCopyPass&) = delete;

    // The rects of `depth` (atlasSize^2 float bits, the compute rasterizer's target) into `atlas`;
    // fresh: the whole atlas (rects ignored). Timed and named as `name`.
    void copyFromBuffer(gpu::CommandList& commands, std::string_view name, gpu::BufferHandle depth, gpu::TextureHandle atlas,
                        uint32_t atlasSize, std::span<const gpu::Rect> rects, bool fresh);
    // The rects of `depth` (a D32 depth target of the atlas's size, the hardware rasterizer's) into `atlas`.
    void copyFromImage(gpu::CommandList& commands, std::string_view name, gpu::TextureHandle depth, gpu::TextureHandle atlas,
                       uint32_t atlasSize, std::span<const gpu::Rect> rects, bool fresh);

private:
    struct Target {
        gpu::TextureHandle atlas;
        uint32_t atlasSize;
        std::span<const gpu::Rect> rects;
        bool fresh;
    };
    void copy(gpu::CommandList& commands, std::string_view name, gpu::PipelineHandle pipeline, const gpu::ResourceUse& sourceUse,
              const gpu::DescriptorWrite& sourceWrite, const Target& target);
    void release();
    void dispatchRects(gpu::CommandList& commands, const Target& target);
    gpu::Device& device_;
    gpu::PipelineHandle fromBuffer_, fromImage_;
    gpu::SamplerHandle pointSampler_;
};

}  // namespace penumbra
