#pragma once
// Renders the shadow tiles of a plan into a depth atlas: one viewport + scissor per tile, the light's
// slope-scale bias as dynamic depth-bias state, depth clamp for pancaking, and per-tile caster lists
// from the planner (seed 000 §1.6-§1.9, §4.4-§4.5, §5).
#include <vector>

#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

class ShadowCasterPass {
public:
    ShadowCasterPass(gpu::Device& device, const GpuScene& gpuScene);

    // Clears `atlas` (depth 1 = far, nothing cast) and draws every tile; `atlas` goes from
    // Undefined to ShaderRead.
    void record(gpu::CommandList& commands, const Scene& scene, const std::vector<ShadowTile>& tiles,
                gpu::TextureHandle atlas, uint32_t atlasSize, gpu::BufferHandle frameBuffer, gpu::BufferHandle lightBuffer);

private:
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle depthOnly_;  // shadows "on"
    gpu::PipelineHandle alphaTested_;  // shadows "clip" and "dither"
};

}  // namespace penumbra
