#include "render/screen_space_shadow_pass.h"

#include "core/error.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

ScreenSpaceShadowPass::ScreenSpaceShadowPass(gpu::Device& device, MainPass& mainPass)
    : device_(device), mainPass_(mainPass) {
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "fullscreen.vert";
    desc.fragmentShader = "screen_space_shadows.frag";
    desc.bindings = screenSpaceShadowBindings();
    desc.pushConstantSize = sizeof(gpu_data::ScreenShadowConstants);
    desc.colorFormats = {gpu::Format::R32Float};
    desc.depthTest = desc.depthWrite = false;
    desc.cullMode = gpu::CullMode::None;
    desc.debugName = "screen-space shadow resolve";
    resolve_ = device_.createGraphicsPipeline(desc);
    pointSampler_ = device_.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
    prepass_.passName = "depthPrepass";
    prepass_.variant = prepassVariant();
}

ScreenSpaceShadowPass::~ScreenSpaceShadowPass() {
    releaseTargets();
    device_.destroy(resolve_);
    device_.destroy(pointSampler_);
}

MainPassVariant ScreenSpaceShadowPass::prepassVariant() {
    MainPassVariant variant;
    variant.colorFormat = gpu::Format::RGBA16Float;
    variant.fragmentShader = "normal_prepass.frag";
    variant.drawBlended = false;
    return variant;
}

void ScreenSpaceShadowPass::ensureTargets(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_ && shadows_) return;
    releaseTargets();
    auto make = [&](gpu::Format format, uint32_t usage, const char* name) {
        return device_.createTexture({width, height, format, usage | gpu::kTextureSampled, 1, name});
    };
    depth_ = make(gpu::Format::D32Float, gpu::kTextureDepthTarget, "prepass depth");
    normals_ = make(gpu::Format::RGBA16Float, gpu::kTextureColorTarget, "prepass normals");
    shadows_ = make(gpu::Format::R32Float, gpu::kTextureColorTarget, "screen-space shadows");
    width_ = width;
    height_ = height;
}

void ScreenSpaceShadowPass::releaseTargets() {
    for (gpu::TextureHandle t : {depth_, normals_, shadows_}) device_.destroy(t);
    depth_ = normals_ = shadows_ = {};
    width_ = height_ = 0;
}

gpu::TextureHandle ScreenSpaceShadowPass::record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                                                 const MainPassInputs& inputs, uint32_t mainLightSlot) {
    recordPrepass(commands, scene, view, inputs);
    return recordResolve(commands, view, inputs, mainLightSlot);
}

gpu::TextureHandle ScreenSpaceShadowPass::recordPrepass(gpu::CommandList& commands, const Scene& scene,
                                                        const CameraView& view, const MainPassInputs& inputs) {
    ensureTargets(view.width, view.height);
    commands.beginTimer("depthPrepass");
    MainPass::Target& prepass = prepass_;  // made once: recording it allocates nothing
    prepass.color = normals_;
    prepass.depth = depth_;
    prepass.width = view.width;
    prepass.height = view.height;
    mainPass_.record(commands, scene, view, inputs, prepass_);
    commands.endTimer();
    return depth_;
}

gpu::TextureHandle ScreenSpaceShadowPass::recordResolve(gpu::CommandList& commands, const CameraView& view,
                                                        const MainPassInputs& inputs, uint32_t mainLightSlot) {
    PENUMBRA_ASSERT(depth_ && width_ == view.width && height_ == view.height);  // recordPrepass came first

    commands.beginTimer("screenSpaceShadows");
    std::vector<gpu::ResourceUse>& uses = uses_;  // refilled: its storage is kept
    uses.assign({gpu::discard(shadows_, gpu::Usage::ColorTarget), gpu::use(depth_, gpu::Usage::FragmentSampled),
                 gpu::use(normals_, gpu::Usage::FragmentSampled)});
    addShadingReads(uses, mainPass_.scene(), inputs, false);
    commands.pass("screenSpaceShadows", uses);
    gpu::RenderingDesc rendering;
    rendering.width = view.width;
    rendering.height = view.height;
    const gpu::ColorAttachment color{shadows_, true, {1, 1, 1, 1}};
    rendering.colors = std::span(&color, 1);
    commands.beginRendering(rendering);
    commands.bindPipeline(resolve_);
    std::vector<gpu::DescriptorWrite>& writes = writes_;
    writes.assign(inputs.writes.begin(), inputs.writes.end());
    writes.push_back({gpu_data::kScreenShadowBindingSceneDepth, {}, depth_, pointSampler_});
    writes.push_back({gpu_data::kScreenShadowBindingSceneNormals, {}, normals_, pointSampler_});
    commands.pushDescriptors(writes);
    const gpu_data::ScreenShadowConstants constants{mainLightSlot};
    commands.pushConstants(&constants, sizeof(constants));
    commands.draw(3);
    commands.endRendering();
    commands.endTimer();
    return shadows_;
}

}  // namespace penumbra
