#pragma once
// The depth reduction of the tight cascade fit (issue 13 item 8, SDSM): a depth prepass of the main
// view, read back and reduced on the CPU (shadows/visible_surfaces.h) before the shadow plan. One extra
// submission and readback per frame, only when shadows.directional.fit = tight.
#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "shadows/visible_surfaces.h"

namespace penumbra {

class VisibleSurfacePass {
public:
    VisibleSurfacePass(gpu::Device& device, const GpuScene& gpuScene, MainPass& mainPass)
        : device_(device), gpuScene_(gpuScene), mainPass_(mainPass) {}

    // Draws the opaque and alpha-tested surfaces of `view` (frameBuffer gets the view's FrameData; the
    // caller rewrites it afterwards), waits, and reduces the depth buffer.
    VisibleSurfaces render(const Scene& scene, const CameraView& view, gpu::BufferHandle frameBuffer,
                           gpu::BufferHandle lightBuffer);

private:
    gpu::Device& device_;
    const GpuScene& gpuScene_;
    MainPass& mainPass_;
};

}  // namespace penumbra
