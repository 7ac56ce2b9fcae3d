#pragma once
// Virtual shadow map page marking on the GPU (shaders/virtual_page_mark.comp.glsl): from the main
// view's depth, the request bit of every clipmap page of a directional light that the view's shadow
// lookups will read. shadows/virtual_page_marking.h is the CPU reference and defines the rules and
// the bit layout (shaders/shared/virtual_page_structs.h). The depth comes from the view's D32 depth
// texture (the forward path's prepass) or from the visibility buffer before its resolve
// (virtual_page_mark_visibility.comp).
// - record(): inside a frame (or any command list), after the pass that wrote the depth; the requests
//   stay in requestWords() for the passes that follow (or Device::readBackAtFrameEnd + fromReadback);
// - markNow(): records, submits, waits and reads back (tests, debugging).
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/device.h"
#include "shadows/virtual_page_marking.h"
#include "virtual_page_structs.h"

namespace penumbra {

// The uniform data of one marking: camera, light rotation (clipmapRotationFromWorld), clipmap and the
// filter's margin in texels.
gpu_data::VirtualPageMarkData packVirtualPageMark(const VirtualClipmapConfig& config, const glm::mat4& lightRotation,
                                                  const CameraView& view, float marginTexels);

// Where the view's depth is: a D32 depth texture (any size; sampled) or a visibility buffer of
// width x height 64-bit words whose high halves are the depth bits (render/visibility_pass.h).
struct VirtualPageDepthSource {
    gpu::TextureHandle depth;
    gpu::BufferHandle visibility;
    uint32_t width = 0, height = 0;  // the visibility buffer's pixels (a texture's come from its desc)

    static VirtualPageDepthSource texture(gpu::TextureHandle depth) { return {depth, {}, 0, 0}; }
    static VirtualPageDepthSource visibilityBuffer(gpu::BufferHandle words, uint32_t width, uint32_t height) {
        return {{}, words, width, height};
    }
};

// A pass over the view's pixels in two variants: one sampling a D32 depth texture, one reading the
// visibility buffer (each shader declares its own depth binding), with the texture variant's point sampler.
// The virtual shadow maps' markings (directional clipmaps, spot and point faces) both record through it.
class DepthSourcePipelines {
public:
    // texture, visibility: the two variants' pipelines (shader, bindings, name).
    DepthSourcePipelines(gpu::Device& device, const gpu::ComputePipelineDesc& texture, const gpu::ComputePipelineDesc& visibility);
    ~DepthSourcePipelines();
    DepthSourcePipelines(const DepthSourcePipelines&) = delete;
    DepthSourcePipelines& operator=(const DepthSourcePipelines&) = delete;

    // Declares pass `name` (the depth read, `written` written), binds the variant for `source`, pushes
    // `writes` (at most kMaxWrites) with the depth at depthBinding or visibilityBinding, and dispatches 8 x 8
    // groups over the depth's pixels. Allocates nothing.
    static constexpr size_t kMaxWrites = 7;
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& source, const char* name, gpu::BufferHandle written,
                std::span<const gpu::DescriptorWrite> writes, uint32_t depthBinding, uint32_t visibilityBinding);

private:
    gpu::Device& device_;
    gpu::PipelineHandle texture_, visibility_;
    gpu::SamplerHandle pointSampler_;
};

class VirtualPageMarkPass {
public:
    explicit VirtualPageMarkPass(gpu::Device& device);
    ~VirtualPageMarkPass();
    VirtualPageMarkPass(const VirtualPageMarkPass&) = delete;
    VirtualPageMarkPass& operator=(const VirtualPageMarkPass&) = delete;

    // Clears the request bits and marks them from `depth` (the view's D32 depth, view.width x
    // view.height, sampled by the pass) with `mark` (a VirtualPageMarkData from packVirtualPageMark,
    // e.g. in the frame's upload ring) for `config`, the clipmap `mark` was packed for.
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& source, const gpu::BufferSlice& mark,
                const VirtualClipmapConfig& config);
    // The request bits of the last record (virtualPageRequestWords(config) words), GPU-written.
    gpu::BufferSlice requestWords() const;
    static VirtualPageRequests fromReadback(const uint8_t* bytes, const VirtualClipmapConfig& config);

    // Marks from a depth texture (any state; left sampled) or from a CPU depth image as
    // visibleSurfacesFromDepth reads it (uploaded first), and waits for the requests.
    VirtualPageRequests markNow(gpu::TextureHandle depth, const CameraView& view, const glm::mat4& lightRotation,
                                const VirtualClipmapConfig& config, float marginTexels);
    VirtualPageRequests markNow(const Image& depth, const CameraView& view, const glm::mat4& lightRotation,
                                const VirtualClipmapConfig& config, float marginTexels);

private:
    void ensureRequests(const VirtualClipmapConfig& config);

    gpu::Device& device_;
    DepthSourcePipelines pipelines_;
    gpu::BufferHandle requests_, readback_;  // readback_: markNow's host copy of requests_
    gpu::BufferHandle markNowData_;          // markNow's VirtualPageMarkData
    uint64_t requestBytes_ = 0;
};

}  // namespace penumbra
