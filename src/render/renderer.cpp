#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <optional>

#include "core/error.h"
#include "render/frame_data.h"
#include "render/gpu_scene.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "render/screen_space_shadow_pass.h"
#include "render/shadow_caster_pass.h"
#include "render/shadow_stats_json.h"
#include "render/visible_surface_pass.h"
#include "scene_structs.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

struct Renderer::State {
    gpu::Device& device;
    const Scene& scene;
    GpuScene gpuScene;
    MainPass mainPass;
    ShadowCasterPass casterPass;
    ScreenSpaceShadowPass screenSpacePass;
    VisibleSurfacePass visiblePass;
    gpu::BufferHandle frameBuffer, lightBuffer, directionalShadowBuffer, otherShadowBuffer;
    gpu::SamplerHandle shadowSampler, pointSampler;
    gpu::TextureHandle noScreenShadows;  // bound at binding 9 when the screen-space resolve is off

    State(gpu::Device& d, const Scene& s)
        : device(d), scene(s), gpuScene(d, s), mainPass(d, gpuScene), casterPass(d, gpuScene), screenSpacePass(d, mainPass),
          visiblePass(d, gpuScene, mainPass) {
        frameBuffer = d.createBuffer(sizeof(gpu_data::FrameData), gpu::kBufferUniform, gpu::MemoryKind::HostVisible);
        const size_t maxLights = gpu_data::kMaxDirectionalLights + gpu_data::kMaxOtherLights;
        lightBuffer = d.createBuffer(maxLights * sizeof(gpu_data::LightData), gpu::kBufferStorage, gpu::MemoryKind::HostVisible);
        directionalShadowBuffer = d.createBuffer(sizeof(gpu_data::DirectionalShadowData), gpu::kBufferUniform,
                                                 gpu::MemoryKind::HostVisible);
        otherShadowBuffer = d.createBuffer(sizeof(gpu_data::OtherShadowData), gpu::kBufferUniform,
                                           gpu::MemoryKind::HostVisible);
        // Hardware 2x2 PCF: "fragment depth <= stored depth -> lit"; outside the atlas counts as lit.
        shadowSampler = d.createSampler({gpu::Filter::Linear, false, gpu::AddressMode::ClampToBorderWhite, true,
                                         gpu::CompareOp::LessOrEqual});
        pointSampler = d.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
        noScreenShadows = d.createTexture(
            {1, 1, gpu::Format::R32Float, gpu::kTextureSampled | gpu::kTextureColorTarget, 1, "no screen shadows"});
        gpu::CommandList commands = d.beginCommands();
        commands.transition(noScreenShadows, gpu::TextureState::Undefined, gpu::TextureState::ShaderRead);
        d.submitAndWait(commands);
    }
};

Renderer::Renderer(gpu::Device& device, const Scene& scene) : state_(std::make_unique<State>(device, scene)) {}
Renderer::~Renderer() = default;

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings) {
    return render(request, settings, resolveCameraView(state_->scene, request.width, request.height));
}

namespace {

gpu_data::FrameData makeFrameData(const CameraView& view, const PackedLights& lights, const RenderRequest& request,
                                  const Settings& settings, bool screenSpaceShadows) {
    gpu_data::FrameData frame = cameraFrameData(view);
    uint32_t mode = gpu_data::kOutputColor;
    if (request.output == OutputMode::ShadowAov) mode = gpu_data::kOutputShadowAov;
    if (request.output == OutputMode::CascadesAov) mode = gpu_data::kOutputCascadesAov;
    frame.counts = glm::uvec4(lights.directionalCount, lights.otherCount, mode, request.aovLight);
    frame.params = glm::vec4(settings.render.exposure, settings.render.ambient, screenSpaceShadows ? 1.0f : 0.0f, 0.0f);
    return frame;
}

Image toOutputImage(const Image& rgba, OutputMode output) {
    const uint32_t channels = output == OutputMode::ShadowAov ? 1 : 3;
    Image image(rgba.width, rgba.height, channels);
    for (size_t p = 0; p < size_t(rgba.width) * rgba.height; ++p)
        for (uint32_t c = 0; c < channels; ++c) image.pixels[p * channels + c] = rgba.pixels[p * 4 + c];
    return image;
}

// 32-bit float depth (0 = near the light, 1 = empty) to 8-bit gray.
Image depthToGray(const Image& depth) {
    Image gray(depth.width, depth.height, 1);
    for (size_t p = 0; p < size_t(depth.width) * depth.height; ++p) {
        float value = 0.0f;
        std::memcpy(&value, &depth.pixels[p * 4], sizeof(float));
        gray.pixels[p] = uint8_t(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    return gray;
}

// --dump-atlas: the directional atlas on the left, the spot/point atlas to its right (when it has
// tiles), top-aligned; the rest is white (depth 1, empty).
Image sideBySide(const Image& left, const Image& right) {
    Image image(left.width + right.width, std::max(left.height, right.height), 1);
    std::fill(image.pixels.begin(), image.pixels.end(), uint8_t(255));
    for (uint32_t y = 0; y < left.height; ++y)
        std::copy_n(&left.pixels[size_t(y) * left.width], left.width, &image.pixels[size_t(y) * image.width]);
    for (uint32_t y = 0; y < right.height; ++y)
        std::copy_n(&right.pixels[size_t(y) * right.width], right.width,
                    &image.pixels[size_t(y) * image.width + left.width]);
    return image;
}

}  // namespace

namespace {

// The textures one frame renders into; made per frame since sizes follow the plan and the request.
struct FrameTargets {
    gpu::TextureHandle atlas, otherAtlas, color, depth;
    uint32_t atlasSize = 1, otherAtlasSize = 1;
    gpu::Format colorFormat = gpu::Format::RGBA8Srgb;

    FrameTargets(gpu::Device& device, const ShadowFrame& plan, const CameraView& view, OutputMode output) : device_(device) {
        const uint32_t depthUsage = gpu::kTextureDepthTarget | gpu::kTextureSampled;
        atlasSize = plan.directional.atlas.tileCount > 0 ? plan.directional.atlas.atlasSize : 1u;
        atlas = device.createTexture({atlasSize, atlasSize, gpu::Format::D32Float, depthUsage, 1, "directional atlas"});
        otherAtlasSize = plan.other.atlas.tileCount > 0 ? plan.other.atlas.atlasSize : 1u;
        otherAtlas = device.createTexture({otherAtlasSize, otherAtlasSize, gpu::Format::D32Float, depthUsage, 1, "other atlas"});
        colorFormat = output == OutputMode::Color ? gpu::Format::RGBA8Srgb : gpu::Format::RGBA8Unorm;
        color = device.createTexture(
            {view.width, view.height, colorFormat, gpu::kTextureColorTarget | gpu::kTextureTransferSrc, 1, "color"});
        depth = device.createTexture({view.width, view.height, gpu::Format::D32Float, gpu::kTextureDepthTarget, 1, "depth"});
    }
    ~FrameTargets() {
        for (gpu::TextureHandle t : {atlas, otherAtlas, color, depth}) device_.destroy(t);
    }
    FrameTargets(const FrameTargets&) = delete;
    FrameTargets& operator=(const FrameTargets&) = delete;

private:
    gpu::Device& device_;
};

// Bindings 0-8, 12, 13 of the scene passes: scene buffers, both shadow blocks and both atlases.
MainPassInputs shadowedSceneInputs(const GpuScene& gpuScene, gpu::BufferHandle frame, gpu::BufferHandle lights,
                                   gpu::BufferHandle directionalShadows, gpu::BufferHandle otherShadows,
                                   const FrameTargets& targets, gpu::SamplerHandle shadowSampler,
                                   gpu::SamplerHandle depthSampler) {
    MainPassInputs inputs;
    inputs.bindings = sceneBindings();
    inputs.writes = sceneDescriptorWrites(gpuScene, frame, lights);
    inputs.bindings.push_back({5, gpu::DescriptorType::UniformBuffer});
    inputs.bindings.push_back({6, gpu::DescriptorType::SampledTexture});
    inputs.bindings.push_back({7, gpu::DescriptorType::UniformBuffer});
    inputs.bindings.push_back({8, gpu::DescriptorType::SampledTexture});
    inputs.writes.push_back({5, directionalShadows, {}, {}});
    inputs.writes.push_back({6, {}, targets.atlas, shadowSampler});
    inputs.writes.push_back({7, otherShadows, {}, {}});
    inputs.writes.push_back({8, {}, targets.otherAtlas, shadowSampler});
    // 12, 13: the same atlases as raw depth (receiver-plane compare, blocker search; shaders/shadows.glsl).
    inputs.bindings.push_back({12, gpu::DescriptorType::SampledTexture});
    inputs.bindings.push_back({13, gpu::DescriptorType::SampledTexture});
    inputs.writes.push_back({12, {}, targets.atlas, depthSampler});
    inputs.writes.push_back({13, {}, targets.otherAtlas, depthSampler});
    return inputs;
}

MainPass::Target mainTarget(const FrameTargets& targets, const RenderRequest& request, const ShadowFrame& plan,
                            const Settings& settings) {
    MainPass::Target target;
    target.color = targets.color;
    target.colorFormat = targets.colorFormat;
    target.depth = targets.depth;
    // Shadow AOV: 1 (lit) where no geometry is; colour and cascades: black background. The AOVs show
    // the opaque surface, so blended draws are left out of them.
    if (request.output == OutputMode::ShadowAov) std::fill(target.clearColor, target.clearColor + 4, 1.0f);
    target.drawBlended = request.output == OutputMode::Color;
    // Seed 001 §6.4: the lit pass is specialized to the spot/point shadow kinds this frame uses.
    target.specialization = {{2, plan.other.specializationMode}, {3, uint32_t(settings.shadows.spot.filter)}};
    return target;
}

}  // namespace

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings, const CameraView& view) {
    State& s = *state_;
    validateSettings(settings);
    if (request.output != OutputMode::Color && request.aovLight >= s.scene.lights.size() && !s.scene.lights.empty())
        throw Error("--light " + std::to_string(request.aovLight) + " does not exist (the scene has " +
                    std::to_string(s.scene.lights.size()) + " lights)");
    RenderResult result;
    const auto planStart = std::chrono::steady_clock::now();
    std::optional<VisibleSurfaces> visible;  // the tight cascade fit's depth reduction (issue 13 item 8)
    if (settings.shadows.directional.fit == CascadeFit::Tight)
        visible = s.visiblePass.render(s.scene, view, s.frameBuffer, s.lightBuffer);
    const ShadowFrame plan = ShadowPlanner::plan(s.scene, view, settings.shadows, visible ? &*visible : nullptr);
    const PackedLights lights = packLights(s.scene, [&](uint32_t i) {
        const bool directional = s.scene.lights[i].type == LightType::Directional;
        const int32_t slot = (directional ? plan.directional.slotOfSceneLight : plan.other.slotOfSceneLight).at(i);
        return slot >= 0 ? uint32_t(slot) : kNoShadowSlot;
    });
    result.stats.cpuPlanMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - planStart).count();
    result.stats.warnings = lights.warnings;
    result.stats.warnings.insert(result.stats.warnings.end(), plan.other.warnings.begin(), plan.other.warnings.end());
    result.stats.shadowStatsJson = shadowStatsJson(plan);

    const bool screenSpace = settings.shadows.screenSpace && !plan.directional.lights.empty();
    const gpu_data::FrameData frame = makeFrameData(view, lights, request, settings, screenSpace);
    s.device.writeBuffer(s.frameBuffer, &frame, sizeof(frame));
    if (!lights.lights.empty())
        s.device.writeBuffer(s.lightBuffer, lights.lights.data(), lights.lights.size() * sizeof(lights.lights[0]));
    s.device.writeBuffer(s.directionalShadowBuffer, &plan.directional.gpu, sizeof(plan.directional.gpu));
    s.device.writeBuffer(s.otherShadowBuffer, &plan.other.gpu, sizeof(plan.other.gpu));
    const FrameTargets targets(s.device, plan, view, request.output);

    gpu::CommandList commands = s.device.beginCommands();
    commands.beginTimer("shadows.directional");
    s.casterPass.record(commands, s.scene, plan.directional.tiles, targets.atlas, targets.atlasSize, s.frameBuffer,
                        s.lightBuffer);
    commands.endTimer();
    commands.beginTimer("shadows.other");
    s.casterPass.record(commands, s.scene, plan.other.tiles, targets.otherAtlas, targets.otherAtlasSize, s.frameBuffer,
                        s.lightBuffer);
    commands.endTimer();

    MainPassInputs inputs = shadowedSceneInputs(s.gpuScene, s.frameBuffer, s.lightBuffer, s.directionalShadowBuffer,
                                                s.otherShadowBuffer, targets, s.shadowSampler, s.pointSampler);
    gpu::TextureHandle screenShadows = s.noScreenShadows;
    if (screenSpace) screenShadows = s.screenSpacePass.record(commands, s.scene, view, inputs, 0);
    inputs.bindings.push_back({9, gpu::DescriptorType::SampledTexture});
    inputs.writes.push_back({9, {}, screenShadows, s.pointSampler});

    commands.beginTimer("main");
    commands.transition(targets.color, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    commands.transition(targets.depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    s.mainPass.record(commands, s.scene, view, inputs, mainTarget(targets, request, plan, settings));
    commands.endTimer();
    s.device.submitAndWait(commands);

    result.stats.gpuTimings = s.device.lastTimings();
    result.image = toOutputImage(s.device.readTexture(targets.color, gpu::TextureState::ColorTarget), request.output);
    if (request.captureAtlas) {
        result.atlas = depthToGray(s.device.readTexture(targets.atlas, gpu::TextureState::ShaderRead));
        if (plan.other.atlas.tileCount > 0)
            result.atlas = sideBySide(result.atlas,
                                      depthToGray(s.device.readTexture(targets.otherAtlas, gpu::TextureState::ShaderRead)));
    }
    s.screenSpacePass.releaseTargets();
    return result;
}

}  // namespace penumbra
