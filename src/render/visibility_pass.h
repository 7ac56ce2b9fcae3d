#pragma once
// The visibility-buffer main view (shaders/shared/visibility_structs.h): opaque and
// alpha-tested triangles rasterized in compute into a 64-bit word per pixel (depth | instance +
// triangle), then one full-screen compute resolve that shades every pixel with the forward lit
// pass's functions (shade_surface.glsl) and writes the colour and depth targets, on which the
// forward pass draws the blended materials afterwards (MainPass::Target::opaqueDone).
// Raster passes as the shadow atlases' compute rasterizer: per instance batch (small triangles at
// once, large ones queued), per large triangle (split into chunks), per chunk; a full queue makes
// the earlier pass draw the rest itself, so nothing is dropped. The instances come from the shadow
// culling pass's main-view lists (render.viewCulling): with occlusion culling the early list is
// rasterized, a depth pyramid built from the visibility buffer, the late list culled against it and
// rasterized on top (cull_structs.h).
// On CPU devices (lavapipe) the resolve runs as a full-screen fragment pass of the same functions
// (visibility_resolve.frag): Mesa 22.3's lavapipe corrupts its heap now and then running the shading
// functions in a compute shader (seen as crashes in later, unrelated calls; it does not happen with the
// same code in a fragment shader). GPUs run the compute resolve.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "cull_structs.h"
#include "gpu/device.h"
#include "penumbra/render_settings.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "render/shadow_culling_pass.h"
#include "shadows/cull_packing.h"
#include "visibility_structs.h"

namespace penumbra {

class VisibilityPass {
public:
    VisibilityPass(gpu::Device& device, const GpuScene& gpuScene);
    ~VisibilityPass();
    VisibilityPass(const VisibilityPass&) = delete;
    VisibilityPass& operator=(const VisibilityPass&) = delete;

    // Whether the device and scene allow it: 64-bit buffer atomics, instance + triangle ids in 32 bits.
    static bool supported(const gpu::Device& device, const GpuScene& gpuScene);

    struct Target {
        gpu::TextureHandle color, depth;  // colour written; depth written when depthRead (or by the fragment resolve)
        gpu::Format colorFormat = gpu::Format::RGBA8Srgb;
        uint32_t width = 0, height = 0;
        float clearColor[4] = {0, 0, 0, 1};
        bool backgroundGradient = false;  // where no surface is: render.background's gradient, not clearColor
        // A later pass of the frame reads `depth` (blended draws, the tight cascade fit): else the compute
        // resolve does not copy the view's depth into it (the fragment resolve writes it anyway).
        bool depthRead = true;
        std::vector<gpu::SpecConstant> specialization;  // the lit pass's (ids >= 2)
    };
    // Builds the resolve pipeline of these lit-pass constants and the buffers of this size unless they
    // exist (before recording).
    void prepare(const std::vector<gpu::SpecConstant>& specialization, gpu::Format colorFormat, uint32_t width,
                 uint32_t height) {
        resolvePipeline(specialization, colorFormat);
        ensureSize(width, height);
    }
    bool fragmentResolve() const { return fragmentResolve_; }
    // inputs.writes: the shaded scene bindings 0-16; `cullFrame` holds CullFrame::camera
    // of this view and `culling`. meshletCulling: skip meshlets outside the view or facing away
    // (render.meshletCulling). Timed as main/cull, main/raster, main/occlusion (pyramid and late
    // culling), main/rasterLate, main/resolve, main/copy.
    void record(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                ShadowCullingPass& culling, const gpu::BufferSlice& cullFrame, ViewCulling viewCulling,
                bool meshletCulling);
    // The meshlets skipped in the last recorded frame (RasterCounters::meshletsOutside and
    // meshletsFacingAway, then two reserved words), for the frame-end readback.
    // The two halves of record(), for a frame that needs the view's depth before it shades (the virtual
    // shadow maps mark their pages from visibilityBuffer()): the culling and rasterization, then the
    // resolve (and copy). Between them the visibility buffer holds every pixel's depth.
    void recordGeometry(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                        ShadowCullingPass& culling, const gpu::BufferSlice& cullFrame, ViewCulling viewCulling,
                        bool meshletCulling);
    void recordShading(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target);
    // 64-bit words per pixel (width x height): reversed-Z depth bits << 32 | the triangle's ids.
    gpu::BufferHandle visibilityBuffer() const { return visibility_; }
    gpu::BufferSlice meshletCounts() const {
        return {counters_, offsetof(gpu_data::RasterCounters, meshletsOutside), 4 * sizeof(uint32_t)};
    }

private:
    void create();
    void destroyAll();
    void ensureSize(uint32_t width, uint32_t height);
    gpu::PipelineHandle resolvePipeline(const std::vector<gpu::SpecConstant>& specialization, gpu::Format colorFormat);
    // One phase's rasterization (frame graph passes `name`, name/bin, name/chunks and the sizes);
    // `reads`: rasterReads().
    void recordRaster(gpu::CommandList& commands, std::string_view name, const std::vector<gpu::DescriptorWrite>& writes,
                      const std::vector<gpu::ResourceUse>& reads, gpu_data::VisibilityConstants constants, uint32_t list,
                      bool meshletCulling);
    void recordPyramid(gpu::CommandList& commands);
    gpu_data::VisibilityConstants constantsFor(const Target& target) const;
    void recordResolve(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                       const gpu_data::VisibilityConstants& constants);

    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle raster_, rasterPacked_, bin_, chunks_, args_, pyramid_;
    // The resolve pipelines, one per lit-pass specialization (and colour format for the fragment
    // resolve): a handful, found by a linear search that builds no key.
    struct ResolvePipeline {
        std::vector<gpu::SpecConstant> specialization;
        gpu::Format format = gpu::Format::Undefined;
        gpu::PipelineHandle pipeline;
    };
    std::vector<ResolvePipeline> resolve_;
    DepthPyramidLayout pyramidLayout_;  // of width_ x height_
    // Per-record lists, kept to reuse their storage (a steady frame allocates nothing).
    std::vector<gpu::DescriptorWrite> resolveWrites_, rasterWrites_;
    std::vector<gpu::ResourceUse> resolveUses_, copyUses_, reads_;
    bool fragmentResolve_ = false;
    gpu::BufferHandle counters_, large_, chunkList_, visibility_, depth_, pyramidTexels_;
    // The compute resolve's colour (RGBA8 UNORM storage, the target's bytes: sRGB-encoded for an sRGB
    // target), copied image to image into the target.
    gpu::TextureHandle color_;
    uint32_t width_ = 0, height_ = 0;
    static constexpr uint32_t kLargeCapacity = 1u << 18, kChunkCapacity = 1u << 20;
};

}  // namespace penumbra
