#include "render/screen_space_shadow_pass.h"

namespace penumbra {

gpu::TextureHandle ScreenSpaceShadowPass::record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                                                 const MainPassInputs& inputs, uint32_t mainLightSlot) {
    if (!resolve_) {
        gpu::GraphicsPipelineDesc desc;
        desc.vertexShader = "fullscreen.vert";
        desc.fragmentShader = "screen_space_shadows.frag";
        desc.bindings = inputs.bindings;
        desc.bindings.push_back({10, gpu::DescriptorType::SampledTexture});
        desc.bindings.push_back({11, gpu::DescriptorType::SampledTexture});
        desc.pushConstantSize = sizeof(glm::uvec4);
        desc.colorFormats = {gpu::Format::R32Float};
        desc.depthTest = desc.depthWrite = false;
        desc.cullMode = gpu::CullMode::None;
        resolve_ = device_.createGraphicsPipeline(desc);
        pointSampler_ = device_.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
    }
    auto makeTarget = [&](gpu::Format format, uint32_t usage) {
        targets_.push_back(device_.createTexture({view.width, view.height, format, usage | gpu::kTextureSampled, 1, "ss"}));
        return targets_.back();
    };
    const gpu::TextureHandle depth = makeTarget(gpu::Format::D32Float, gpu::kTextureDepthTarget);
    const gpu::TextureHandle normals = makeTarget(gpu::Format::RGBA16Float, gpu::kTextureColorTarget);
    const gpu::TextureHandle shadows = makeTarget(gpu::Format::R32Float, gpu::kTextureColorTarget);

    commands.beginTimer("depthPrepass");
    commands.transition(depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    commands.transition(normals, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    MainPass::Target prepass;
    prepass.color = normals;
    prepass.colorFormat = gpu::Format::RGBA16Float;
    prepass.depth = depth;
    prepass.fragmentShader = "normal_prepass.frag";
    prepass.drawBlended = false;
    mainPass_.record(commands, scene, view, inputs, prepass);
    commands.transition(depth, gpu::TextureState::DepthTarget, gpu::TextureState::ShaderRead);
    commands.transition(normals, gpu::TextureState::ColorTarget, gpu::TextureState::ShaderRead);
    commands.endTimer();

    commands.beginTimer("screenSpaceShadows");
    commands.transition(shadows, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    gpu::RenderingDesc rendering;
    rendering.width = view.width;
    rendering.height = view.height;
    rendering.colors = {gpu::ColorAttachment{shadows, true, {1, 1, 1, 1}}};
    commands.beginRendering(rendering);
    commands.bindPipeline(resolve_);
    std::vector<gpu::DescriptorWrite> writes = inputs.writes;
    writes.push_back({10, {}, depth, pointSampler_});
    writes.push_back({11, {}, normals, pointSampler_});
    commands.pushDescriptors(writes);
    const glm::uvec4 slot(mainLightSlot, 0, 0, 0);
    commands.pushConstants(&slot, sizeof(slot));
    commands.draw(3);
    commands.endRendering();
    commands.transition(shadows, gpu::TextureState::ColorTarget, gpu::TextureState::ShaderRead);
    commands.endTimer();
    return shadows;
}

void ScreenSpaceShadowPass::releaseTargets() {
    for (gpu::TextureHandle t : targets_) device_.destroy(t);
    targets_.clear();
}

}  // namespace penumbra
