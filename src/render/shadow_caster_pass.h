#pragma once
// Renders the shadow tiles of a plan into a depth atlas: one viewport + scissor per tile, the light's
// slope-scale bias as dynamic depth-bias state, depth clamp for pancaking, and per-tile caster lists
// from the planner (seed 000 §1.6-§1.9, §4.4-§4.5, §5).
#include <string>
#include <vector>

#include "gpu/device.h"
#include "penumbra/renderer.h"
#include "render/gpu_scene.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

class ShadowCasterPass {
public:
    ShadowCasterPass(gpu::Device& device, const GpuScene& gpuScene, const Scene& scene);
    ~ShadowCasterPass();
    ShadowCasterPass(const ShadowCasterPass&) = delete;
    ShadowCasterPass& operator=(const ShadowCasterPass&) = delete;

    // Clears `atlas` (depth 1 = far, nothing cast) and draws every tile; `atlas` goes from
    // Undefined to ShaderRead. Returns what it drew, named `passName`.
    AtlasDrawStats record(gpu::CommandList& commands, const Scene& scene, const std::vector<ShadowTile>& tiles,
                          gpu::TextureHandle atlas, uint32_t atlasSize, const std::vector<gpu::DescriptorWrite>& writes,
                          const std::string& passName);

private:
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle depthOnly_;    // shadows "on"
    gpu::PipelineHandle alphaTested_;  // shadows "clip" and "dither"
    std::vector<std::vector<const DrawItem*>> drawsOfInstance_;  // the planner's lists select draws by instance
};

}  // namespace penumbra
