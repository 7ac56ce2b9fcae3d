#pragma once
// The depth reduction of the tight cascade fit (SDSM, "Sample Distribution Shadow Maps"): which surfaces a
// view shows, from its depth, reduced on the CPU (shadows/visible_surfaces.h) for the shadow plan.
// - now(): a depth prepass of the view, waited for and read back whole: exact, for one-shot frames
//   (render()), and for the first frame of a real-time run;
// - recordSubsample(): after a real-time frame's main pass, every kStride-th pixel of its depth goes
//   into the frame's readback, and fromReadback() reduces it once the frame is done: the next frames
//   plan with it (a frame or two late, no wait).
// Targets and buffers live across frames.
#include <cstdint>
#include <vector>

#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "shadows/visible_surfaces.h"

namespace penumbra {

class VisibleSurfacePass {
public:
    static constexpr uint32_t kStride = 4;

    VisibleSurfacePass(gpu::Device& device, const GpuScene& gpuScene, MainPass& mainPass);
    ~VisibleSurfacePass();
    VisibleSurfacePass(const VisibleSurfacePass&) = delete;
    VisibleSurfacePass& operator=(const VisibleSurfacePass&) = delete;

    VisibleSurfaces now(const Scene& scene, const CameraView& view);
    // `depth`: the frame's main depth target, in DepthTarget state (left there). Returns where the
    // subsample starts in the frame's readback.
    uint64_t recordSubsample(gpu::CommandList& commands, gpu::TextureHandle depth, const CameraView& view);
    // Reduces the subsample into `visible` (replaced; its storage reused).
    static void fromReadback(const uint8_t* bytes, const CameraView& view, VisibleSurfaces& visible);
    static uint64_t readbackBytes(const CameraView& view);

private:
    void ensureTargets(uint32_t width, uint32_t height);

    gpu::Device& device_;
    const GpuScene& gpuScene_;
    MainPass& mainPass_;
    gpu::BufferHandle frame_;  // FrameData of now()'s view
    gpu::PipelineHandle subsample_;
    gpu::SamplerHandle pointSampler_;
    gpu::TextureHandle normals_, depth_;  // depth_: TransferSrc too (read back by now())
    gpu::BufferHandle depths_, readback_;
    uint32_t width_ = 0, height_ = 0;
};

}  // namespace penumbra
