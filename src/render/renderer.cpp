#include "render/renderer.h"

#include <chrono>

#include "core/error.h"
#include "render/gpu_scene.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "scene_structs.h"

namespace penumbra {

struct Renderer::State {
    gpu::Device& device;
    const Scene& scene;
    GpuScene gpuScene;
    MainPass mainPass;
    gpu::BufferHandle frameBuffer;
    gpu::BufferHandle lightBuffer;

    State(gpu::Device& d, const Scene& s)
        : device(d), scene(s), gpuScene(d, s), mainPass(d, gpuScene) {
        frameBuffer = d.createBuffer(sizeof(gpu_data::FrameData), gpu::kBufferUniform, gpu::MemoryKind::HostVisible);
        const size_t maxLights = gpu_data::kMaxDirectionalLights + gpu_data::kMaxOtherLights;
        lightBuffer = d.createBuffer(maxLights * sizeof(gpu_data::LightData), gpu::kBufferStorage, gpu::MemoryKind::HostVisible);
    }
};

Renderer::Renderer(gpu::Device& device, const Scene& scene) : state_(std::make_unique<State>(device, scene)) {}
Renderer::~Renderer() = default;

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings) {
    return render(request, settings, resolveCameraView(state_->scene, request.width, request.height));
}

namespace {

gpu_data::FrameData makeFrameData(const CameraView& view, const PackedLights& lights, const RenderRequest& request,
                                  const Settings& settings) {
    gpu_data::FrameData frame{};
    frame.clipFromWorld = view.clipFromWorld;
    frame.viewFromWorld = view.viewFromWorld;
    frame.wsCameraPosition = glm::vec4(view.wsPosition, 1.0f);
    frame.viewport = glm::vec4(float(view.width), float(view.height), 1.0f / float(view.width), 1.0f / float(view.height));
    uint32_t mode = gpu_data::kOutputColor;
    if (request.output == OutputMode::ShadowAov) mode = gpu_data::kOutputShadowAov;
    if (request.output == OutputMode::CascadesAov) mode = gpu_data::kOutputCascadesAov;
    frame.counts = glm::uvec4(lights.directionalCount, lights.otherCount, mode, request.aovLight);
    frame.params = glm::vec4(settings.render.exposure, settings.render.ambient, 0.0f, 0.0f);
    return frame;
}

Image toOutputImage(const Image& rgba, OutputMode output) {
    const uint32_t channels = output == OutputMode::ShadowAov ? 1 : 3;
    Image image(rgba.width, rgba.height, channels);
    for (size_t p = 0; p < size_t(rgba.width) * rgba.height; ++p)
        for (uint32_t c = 0; c < channels; ++c) image.pixels[p * channels + c] = rgba.pixels[p * 4 + c];
    return image;
}

}  // namespace

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings, const CameraView& view) {
    State& s = *state_;
    validateSettings(settings);  // settings built in code get the same checks as parsed ones
    if (request.output != OutputMode::Color && request.aovLight >= s.scene.lights.size() && !s.scene.lights.empty())
        throw Error("--light " + std::to_string(request.aovLight) + ": the scene has " +
                    std::to_string(s.scene.lights.size()) + " lights");
    RenderResult result;
    const auto planStart = std::chrono::steady_clock::now();
    const PackedLights lights = packLights(s.scene, [](uint32_t) { return kNoShadowSlot; });
    result.stats.cpuPlanMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - planStart).count();
    result.stats.warnings = lights.warnings;
    const gpu_data::FrameData frame = makeFrameData(view, lights, request, settings);
    s.device.writeBuffer(s.frameBuffer, &frame, sizeof(frame));
    if (!lights.lights.empty())
        s.device.writeBuffer(s.lightBuffer, lights.lights.data(), lights.lights.size() * sizeof(lights.lights[0]));

    const gpu::Format colorFormat = request.output == OutputMode::Color ? gpu::Format::RGBA8Srgb : gpu::Format::RGBA8Unorm;
    const gpu::TextureHandle color = s.device.createTexture(
        {view.width, view.height, colorFormat, gpu::kTextureColorTarget | gpu::kTextureTransferSrc, 1, "color"});
    const gpu::TextureHandle depth = s.device.createTexture(
        {view.width, view.height, gpu::Format::D32Float, gpu::kTextureDepthTarget | gpu::kTextureSampled, 1, "depth"});

    gpu::CommandList commands = s.device.beginCommands();
    commands.transition(color, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    commands.transition(depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    MainPassInputs inputs{s.frameBuffer, s.lightBuffer, {}, {}};
    // Shadow AOV: 1 (lit) where no geometry is; colour: black background.
    const float white[4] = {1, 1, 1, 1}, black[4] = {0, 0, 0, 1};
    commands.beginTimer("main");
    s.mainPass.record(commands, s.scene, view, inputs, color, colorFormat, depth,
                      request.output == OutputMode::ShadowAov ? white : black, request.output == OutputMode::Color);
    commands.endTimer();
    s.device.submitAndWait(commands);
    result.stats.gpuTimings = s.device.lastTimings();
    result.image = toOutputImage(s.device.readTexture(color, gpu::TextureState::ColorTarget), request.output);
    s.device.destroy(color);
    s.device.destroy(depth);
    return result;
}

}  // namespace penumbra
