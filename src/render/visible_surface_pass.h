#pragma once
// The depth reduction of the tight cascade fit (SDSM, "Sample Distribution Shadow Maps"): which surfaces a
// view shows, from its depth, for the shadow plan (shadows/visible_surfaces.h).
// - now(): a depth prepass of the view, waited for and read back whole, every pixel reduced on the CPU:
//   exact, for one-shot frames (render()), and for the first frame of a real-time run;
// - recordBounds(): after a real-time frame's main pass, visible_bounds.comp reduces the view's depth
//   on the GPU to its view-depth range and per-bin bounds in the frame's directional lights' spaces
//   (VisibleDepthBins); the frame reads back those words (120 KiB, whatever the view's size), which fromReadback()
//   decodes once the frame is done: the next frames plan with them (a frame or two late, no wait).
// Targets and buffers live across frames.
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "shadows/visible_surfaces.h"
#include "visible_bounds_structs.h"

namespace penumbra {

class VisibleSurfacePass {
public:
    VisibleSurfacePass(gpu::Device& device, const GpuScene& gpuScene, MainPass& mainPass);
    ~VisibleSurfacePass();
    VisibleSurfacePass(const VisibleSurfacePass&) = delete;
    VisibleSurfacePass& operator=(const VisibleSurfacePass&) = delete;

    VisibleSurfaces now(const Scene& scene, const CameraView& view);

    // Records the reduction of `depth` (the view's D32 depth) with `data` (packVisibleBounds, uploaded
    // by the caller before the frame's first readback); returns where its words start in the frame's
    // readback. Allocates nothing once the first call made its buffer.
    uint64_t recordBounds(gpu::CommandList& commands, gpu::TextureHandle depth, const gpu::BufferSlice& data);
    static constexpr uint64_t kReadbackBytes = uint64_t(gpu_data::kVisibleBoundsWords) * 4;
    // Decodes a recorded reduction's words into `visible` (replaced; its storage reused).
    static void fromReadback(const uint8_t* bytes, const gpu_data::VisibleBoundsData& data, VisibleSurfaces& visible);
    // Records, submits, waits and decodes (tests): `depth` sampled as a D32 texture of the view's size.
    VisibleSurfaces boundsNow(gpu::TextureHandle depth, const CameraView& view, std::span<const glm::mat4> lightRotations,
                              float vsShadowDistance);

private:
    void ensureTargets(uint32_t width, uint32_t height);
    void recordReduction(gpu::CommandList& commands, gpu::TextureHandle depth, const gpu::BufferSlice& data);

    gpu::Device& device_;
    const GpuScene& gpuScene_;
    MainPass& mainPass_;
    gpu::BufferHandle frame_;  // FrameData of now()'s view
    gpu::PipelineHandle bounds_;
    gpu::SamplerHandle pointSampler_;
    gpu::TextureHandle normals_, depth_;  // depth_: TransferSrc too (read back by now())
    gpu::BufferHandle words_;             // the reduction's keys (visible_bounds_structs.h)
    gpu::BufferHandle readback_;          // now()'s depth
    gpu::BufferHandle boundsNowData_, boundsReadback_;  // boundsNow()'s VisibleBoundsData and words
    uint32_t width_ = 0, height_ = 0;
};

// The uniform data of a reduction of `view`'s depth, and what fromReadback decodes its words with: the
// bins from view.zNear to a quarter beyond vsShadowDistance (the farthest view depth the plan asks
// about); the spaces `lightRotations` (at most kVisibleBoundsSpaces - 1, lightRotationFromWorld), then
// the world's.
gpu_data::VisibleBoundsData packVisibleBounds(const CameraView& view, std::span<const glm::mat4> lightRotations,
                                              float vsShadowDistance);

}  // namespace penumbra
