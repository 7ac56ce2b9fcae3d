#pragma once
// URP's screen-space shadow resolve (seed 004): a depth + normal prepass, then a full-screen pass that
// writes the main directional light's shadow term into a screen-sized R32F texture for the lit pass.
#include "gpu/device.h"
#include "render/main_pass.h"

namespace penumbra {

class ScreenSpaceShadowPass {
public:
    ScreenSpaceShadowPass(gpu::Device& device, MainPass& mainPass) : device_(device), mainPass_(mainPass) {}

    // Records prepass + resolve; returns the R32F shadow texture in ShaderRead state (caller destroys).
    gpu::TextureHandle record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                              const MainPassInputs& inputs, uint32_t mainLightSlot);
    void releaseTargets();

private:
    gpu::Device& device_;
    MainPass& mainPass_;
    gpu::PipelineHandle resolve_;
    gpu::SamplerHandle pointSampler_;
    std::vector<gpu::TextureHandle> targets_;
};

}  // namespace penumbra
