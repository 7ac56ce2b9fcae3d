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
    // `scene` is the one gpuScene was made from: its materials say which pipelines a variant needs.
    MainPass(gpu::Device& device, const GpuScene& gpuScene, const Scene& scene, PipelineWarmup warmup)
        : device_(device), scene_(gpuScene), warmup_(warmup) {
        partitionDraws(scene);
    }
    ~MainPass();
    MainPass(const MainPass&) = delete;
    MainPass& operator=(const MainPass&) = delete;

    // Whether a pass of `variant` draws blended materials (the scene has some and the output shows them).
    bool drawsBlended(const MainPassVariant& variant) const { return variant.drawBlended && !blendedDraws_.empty(); }

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
    // A material changed: the draws are sorted into opaque and blended again (between changes each
    // record reuses the partition: no walk over the scene's draws per frame). A material that makes a
    // new (blended, double-sided) combination appear builds that pipeline of each variant when next used.
    void materialsChanged(const Scene& scene) { partitionDraws(scene); }
    // Starts building a variant (Background: on the worker thread; OnDemand: now) unless it exists.
    void request(const MainPassVariant& variant);
    bool ready(const MainPassVariant& variant);
    const GpuScene& scene() const { return scene_; }

private:
    // A variant's pipelines by [blended][doubleSided]; only the combinations the scene's materials use
    // are built (each lit-pass pipeline is a large compile on a CPU device).
    struct PipelineSet {
        gpu::PipelineHandle pipelines[2][2];
    };
    // Orders variants by format, fragment shader, blended flag and specialization (id, value): the
    // sets are found by the variant itself, with no key built per frame.
    struct VariantLess {
        bool operator()(const MainPassVariant& a, const MainPassVariant& b) const;
    };
    PipelineSet& create(const MainPassVariant& variant, bool async);
    // Builds the set's missing pipelines among the combinations the draws use (slotsUsed_).
    void completeSet(const MainPassVariant& variant, PipelineSet& set, bool async);
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
    void uploadOpaqueCommands(std::array<uint32_t, 2> countBySide);
    void drawOpaque(gpu::CommandList& commands, const PipelineSet& set, const std::vector<gpu::DescriptorWrite>& writes);
    void bindDrawState(gpu::CommandList& commands, gpu::PipelineHandle pipeline, const std::vector<gpu::DescriptorWrite>& writes);
    // The scene's draws by alpha mode, kept until materialsChanged(): the opaque and alpha-tested ones
    // single-sided first (scene order within each), the blended ones in scene order.
    std::vector<const DrawItem*> opaqueDraws_, blendedDraws_;
    // The opaque draws as VkDrawIndexedIndirectCommands in that order, and per sidedness their count
    // ({n0, n1}): a record issues two indirect multi-draws, however many objects the scene has.
    gpu::BufferHandle opaqueCommands_, opaqueCounts_;
    std::array<uint32_t, 2> opaqueCountBySide_ = {};
    bool slotsUsed_[2][2] = {};  // [blended][doubleSided]: some draw has that combination
    // Per-record scratch, kept so that a steady frame allocates nothing.
    std::vector<const DrawItem*> blended_;
    std::vector<gpu::ResourceUse> uses_;
    gpu::RenderingDesc rendering_;
};

}  // namespace penumbra
