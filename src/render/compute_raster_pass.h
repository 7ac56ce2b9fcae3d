#pragma once
// The compute rasterizer of the shadow atlases (issue 10, shaders/shadow_raster.glsl): the tiles of
// an atlas drawn by compute shaders from the GPU culling pass's visible lists into a buffer of depth
// by atomic min, then copied into the atlas's depth image, which the lit pass samples as always.
// Three passes: per visible instance (small triangles rasterized at once, large ones queued), per
// large triangle (split into chunks), per chunk.
#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"

namespace penumbra {

class ComputeRasterPass {
public:
    ComputeRasterPass(gpu::Device& device, const GpuScene& gpuScene);
    ~ComputeRasterPass();
    ComputeRasterPass(const ComputeRasterPass&) = delete;
    ComputeRasterPass& operator=(const ComputeRasterPass&) = delete;

    // Renders culling tiles [firstTile, firstTile + tileCount) into `atlas` (atlasSize^2, D32), which
    // goes from Undefined to ShaderRead, through `depth` (at least atlasSize^2 uints, FrameTargets).
    // `writes`: the scene bindings 0-4.
    void record(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes,
                const gpu::BufferSlice& cullFrame, const ShadowCullingPass& culling, uint32_t firstTile,
                uint32_t tileCount, gpu::TextureHandle atlas, uint32_t atlasSize, gpu::BufferHandle depth);
    // The counters of the last recorded pass (RasterCounters): read back to see dropped triangles.
    gpu::BufferSlice counters() const { return {counters_, 0, 48}; }

private:
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle small_, bin_, chunks_, args_;
    gpu::BufferHandle counters_, large_, chunkList_;
};

}  // namespace penumbra
