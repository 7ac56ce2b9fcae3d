#pragma once
// The forward main pass: opaque and alpha-tested draws, the background (render.background) where
// none of them drew, then alpha-blended draws back to front.
// Unlit materials share the pipelines (the material flag selects the path in the shader). The same
// pass draws the depth + normal prepass of the screen-space resolve with another fragment shader.
//
// Pipeline variants: each target names its specialization constants (the lit pass's spot/point
// shadow kinds and filter) and, optionally, a generic set that gives the same image for every frame.
// PipelineWarmup::OnDemand builds a variant the first time a frame needs it; Background builds them
// on the device's worker thread and draws with the generic set until the specialized one is ready.
#include <array>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gpu/device.h"
#include "penumbra/camera.h"
#include "penumbra/renderer.h"
#include "render/gpu_scene.h"

namespace penumbra {

// Everything set 0 of the scene passes binds (pass_bindings.h: the kSceneBinding* and kLitBinding*
// descriptors); each pipeline takes those it declares (render/pass_layouts.h).
struct MainPassInputs {
    std::vector<gpu::DescriptorWrite> writes;
    // What the shading reads through `writes` besides the scene buffers, for the frame graph: the
    // textures sampled (shadow atlases, then the screen-space shadow texture) and the light cluster
    // masks (none in the visible-surface prepass).
    std::vector<gpu::TextureHandle> sampled;
    gpu::BufferHandle clusterMasks;
    // The virtual shadow maps' page tables: the directional lights' (render/virtual_shadows.h), the spot
    // and point lights' faces' (render/virtual_face_shadows.h).
    std::array<gpu::BufferHandle, 2> virtualPages;
};
// The uses of a pass that binds inputs.writes: the scene buffers and the shading inputs, read by the
// vertex and fragment shaders or (compute) by a compute shader.
void addShadingReads(std::vector<gpu::ResourceUse>& uses, const GpuScene& scene, const MainPassInputs& inputs,
                     bool compute);

// The scene bindings every pass that draws the scene binds: frame data, vertices, instances, materials,
// lights (a fixed array: callers copy it into their lists without a heap allocation).
using SceneWrites = std::array<gpu::DescriptorWrite, 5>;
SceneWrites sceneDescriptorWrites(const GpuScene& gpuScene, const gpu::BufferSlice& frame, const gpu::BufferSlice& lights);

struct MainPassVariant {
    gpu::Format colorFormat = gpu::Format::RGBA8Srgb;
    std::string fragmentShader = "lit.frag";  // "normal_prepass.frag" for the depth prepass
    bool drawBlended = true;                  // the set has the alpha-blended pipelines too
    std::vector<gpu::SpecConstant> specialization;  // ids >= 2
};

class MainPass {
public:
    MainPass(gpu::Device& device, const GpuScene& gpuScene, PipelineWarmup warmup)
        : device_(device), scene_(gpuScene), warmup_(warmup) {}
    ~MainPass();
    MainPass(const MainPass&) = delete;
    MainPass& operator=(const MainPass&) = delete;

    struct Target {
        gpu::TextureHandle color;
        gpu::TextureHandle depth;
        MainPassVariant variant;
        std::vector<gpu::SpecConstant> genericSpecialization;  // empty: the variant has no generic stand-in
        float clearColor[4] = {0, 0, 0, 1};
        bool background = false;  // draw shaders/background.frag.glsl behind the opaque draws (colour output)
        uint32_t width = 0, height = 0;
        // The visibility buffer drew the opaque and alpha-tested surfaces already: keep the targets
        // (colour and depth) and draw only the blended materials on them.
        bool opaqueDone = false;
        const char* passName = "main";  // in the frame graph
    };
    // Records the pass into target.color / target.depth (cleared unless opaqueDone).
    void record(gpu::CommandList& commands, const Scene& scene, const CameraView& view, const MainPassInputs& inputs,
                const Target& target);
    // A material changed: the draws are sorted into opaque and blended again before the next record
    // (until then each record reuses the partition: no walk over the scene's draws per frame).
    void materialsChanged() { partitioned_ = false; }
    // Starts building a variant (Background: on the worker thread; OnDemand: now) unless it exists.
    void request(const MainPassVariant& variant);
    bool ready(const MainPassVariant& variant);
    const GpuScene& scene() const { return scene_; }

private:
    struct PipelineSet {
        gpu::PipelineHandle opaque[2];   // [doubleSided]
        gpu::PipelineHandle blended[2];
    };
    // Orders variants by format, fragment shader, blended flag and specialization (id, value): the
    // sets are found by the variant itself, with no key built per frame.
    struct VariantLess {
        bool operator()(const MainPassVariant& a, const MainPassVariant& b) const;
    };
    PipelineSet& create(const MainPassVariant& variant, bool async);
    bool setReady(const PipelineSet& set);
    void waitFor(const PipelineSet& set);
    const PipelineSet& pipelinesFor(const Target& target);
    gpu::PipelineHandle backgroundPipeline(gpu::Format colorFormat, bool async);
    void drawBackground(gpu::CommandList& commands, const Target& target, const std::vector<gpu::DescriptorWrite>& writes);
    void drawItems(gpu::CommandList& commands, const std::vector<const DrawItem*>& items, const PipelineSet& set,
                   bool blended, const Scene& scene, const std::vector<gpu::DescriptorWrite>& writes);

    gpu::Device& device_;
    const GpuScene& scene_;
    PipelineWarmup warmup_;
    std::map<MainPassVariant, PipelineSet, VariantLess> pipelineSets_;
    std::map<gpu::Format, gpu::PipelineHandle> backgrounds_;  // by colour format
    void partitionDraws(const Scene& scene);
    // The scene's draws by alpha mode (scene order), kept until materialsChanged().
    std::vector<const DrawItem*> opaqueDraws_, blendedDraws_;
    bool partitioned_ = false;
    // Per-record scratch, kept so that a steady frame allocates nothing.
    std::vector<const DrawItem*> blended_;
    std::vector<gpu::ResourceUse> uses_;
    gpu::RenderingDesc rendering_;
};

}  // namespace penumbra
