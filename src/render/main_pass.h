#pragma once
// The forward main pass: opaque and alpha-tested draws, then alpha-blended draws back to front.
// Unlit materials share the pipelines (the material flag selects the path in the shader).
#include <map>
#include <vector>

#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "scene/camera_view.h"

namespace penumbra {

// Set 0 bindings of the main pass beyond the scene buffers (see shaders/bindings.glsl).
struct MainPassInputs {
    gpu::BufferHandle frameBuffer;
    gpu::BufferHandle lightBuffer;
    std::vector<gpu::DescriptorWrite> shadowWrites;  // shadow data and atlases (bindings 5+)
    std::vector<gpu::BindingDesc> shadowBindings;
};

class MainPass {
public:
    MainPass(gpu::Device& device, const GpuScene& gpuScene) : device_(device), scene_(gpuScene) {}

    // Records the pass into colorTarget / depthTarget (both already in their target states).
    void record(gpu::CommandList& commands, const Scene& scene, const CameraView& view, const MainPassInputs& inputs,
                gpu::TextureHandle colorTarget, gpu::Format colorFormat, gpu::TextureHandle depthTarget,
                const float clearColor[4], bool drawBlended);

private:
    struct PipelineSet {
        gpu::PipelineHandle opaque[2];   // [doubleSided]
        gpu::PipelineHandle blended[2];
    };
    const PipelineSet& pipelines(gpu::Format colorFormat, const MainPassInputs& inputs);
    void drawItems(gpu::CommandList& commands, const std::vector<const DrawItem*>& items, const PipelineSet& set,
                   bool blended, const Scene& scene, const std::vector<gpu::DescriptorWrite>& writes);

    gpu::Device& device_;
    const GpuScene& scene_;
    std::map<gpu::Format, PipelineSet> pipelineSets_;
};

std::vector<gpu::DescriptorWrite> sceneDescriptorWrites(const GpuScene& gpuScene, gpu::BufferHandle frame,
                                                        gpu::BufferHandle lights);
std::vector<gpu::BindingDesc> sceneBindings();

}  // namespace penumbra
