#pragma once
// The forward main pass: opaque and alpha-tested draws, then alpha-blended draws back to front.
// Unlit materials share the pipelines (the material flag selects the path in the shader).
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "scene/camera_view.h"

namespace penumbra {

// Everything set 0 of the scene passes binds: the scene buffers (0-4, sceneBindings()) plus the
// shadow data, atlases and screen-space shadow texture (5-9).
struct MainPassInputs {
    std::vector<gpu::BindingDesc> bindings;
    std::vector<gpu::DescriptorWrite> writes;
};

class MainPass {
public:
    MainPass(gpu::Device& device, const GpuScene& gpuScene) : device_(device), scene_(gpuScene) {}

    struct Target {
        gpu::TextureHandle color;
        gpu::Format colorFormat = gpu::Format::RGBA8Srgb;
        gpu::TextureHandle depth;
        std::string fragmentShader = "lit.frag";  // "normal_prepass.frag" for the depth prepass
        float clearColor[4] = {0, 0, 0, 1};
        bool drawBlended = true;
        // Extra specialization constants of the fragment shader (ids >= 2; e.g. the lit pass's spot/point
        // shadow mode and filter). Part of the pipeline cache key.
        std::vector<gpu::SpecConstant> specialization;
    };
    // Records the pass into target.color / target.depth (both already in their target states).
    void record(gpu::CommandList& commands, const Scene& scene, const CameraView& view, const MainPassInputs& inputs,
                const Target& target);

private:
    struct PipelineSet {
        gpu::PipelineHandle opaque[2];   // [doubleSided]
        gpu::PipelineHandle blended[2];
    };
    const PipelineSet& pipelines(const Target& target, const MainPassInputs& inputs);
    void drawItems(gpu::CommandList& commands, const std::vector<const DrawItem*>& items, const PipelineSet& set,
                   bool blended, const Scene& scene, const std::vector<gpu::DescriptorWrite>& writes);

    gpu::Device& device_;
    const GpuScene& scene_;
    using PipelineKey = std::tuple<gpu::Format, std::string, std::vector<std::pair<uint32_t, uint32_t>>>;
    std::map<PipelineKey, PipelineSet> pipelineSets_;
};

std::vector<gpu::DescriptorWrite> sceneDescriptorWrites(const GpuScene& gpuScene, gpu::BufferHandle frame,
                                                        gpu::BufferHandle lights);
std::vector<gpu::BindingDesc> sceneBindings();

}  // namespace penumbra
