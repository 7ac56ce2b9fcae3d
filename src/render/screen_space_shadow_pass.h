#pragma once
// Screen-space shadow resolve (shadows.screenSpace, as Unity URP's screen-space shadows): a depth + normal
// prepass, then a full-screen pass that writes the main directional light's shadow term into a screen-sized
// R32F texture for the lit pass. Its three targets live across frames and are re-made only when the output
// size changes.
#include "gpu/device.h"
#include "render/main_pass.h"

namespace penumbra {

class ScreenSpaceShadowPass {
public:
    ScreenSpaceShadowPass(gpu::Device& device, MainPass& mainPass);
    ~ScreenSpaceShadowPass();
    ScreenSpaceShadowPass(const ScreenSpaceShadowPass&) = delete;
    ScreenSpaceShadowPass& operator=(const ScreenSpaceShadowPass&) = delete;

    static MainPassVariant prepassVariant();
    // Records prepass + resolve (inputs: bindings 0-9, 9 a placeholder); returns the R32F shadow
    // texture in ShaderRead state, owned by this pass.
    gpu::TextureHandle record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                              const MainPassInputs& inputs, uint32_t mainLightSlot);
    // The two halves of record(): the depth + normal prepass (its D32 depth returned, also what the
    // virtual shadow maps mark their pages from on the forward path), then the resolve after it.
    gpu::TextureHandle recordPrepass(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                                     const MainPassInputs& inputs);
    gpu::TextureHandle recordResolve(gpu::CommandList& commands, const CameraView& view, const MainPassInputs& inputs,
                                     uint32_t mainLightSlot);

private:
    void ensureTargets(uint32_t width, uint32_t height);
    void releaseTargets();

    gpu::Device& device_;
    MainPass& mainPass_;
    gpu::PipelineHandle resolve_;
    gpu::SamplerHandle pointSampler_;
    gpu::TextureHandle depth_, normals_, shadows_;
    uint32_t width_ = 0, height_ = 0;
    MainPass::Target prepass_;  // the prepass's target (its variant made once)
    // Per-record lists, kept to reuse their storage.
    std::vector<gpu::ResourceUse> uses_;
    std::vector<gpu::DescriptorWrite> writes_;
};

}  // namespace penumbra
