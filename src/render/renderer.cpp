#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>

#include "core/error.h"
#include "core/stopwatch.h"
#include "render/frame_targets.h"
#include "render/gpu_scene.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "render/readback_images.h"
#include "render/screen_space_shadow_pass.h"
#include "render/shadow_caster_pass.h"
#include "render/shadow_stats_json.h"
#include "scene/scene_edits.h"
#include "scene/scene_validation.h"
#include "scene_structs.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

namespace {

constexpr size_t kMaxLights = gpu_data::kMaxDirectionalLights + gpu_data::kMaxOtherLights;

gpu::Format colorFormatOf(OutputMode output) {
    return output == OutputMode::Color ? gpu::Format::RGBA8Srgb : gpu::Format::RGBA8Unorm;
}

// The lit pass variant for a colour format and the frame's spot/point shadow kinds and filter
// (seed 001 §6.4). The filter only matters when some light is soft, so the others share one variant.
MainPassVariant litVariant(gpu::Format format, uint32_t otherShadowMode, uint32_t spotFilter) {
    MainPassVariant variant;
    variant.colorFormat = format;
    variant.drawBlended = format == gpu::Format::RGBA8Srgb;  // the AOVs show the opaque surface only
    const bool soft = (otherShadowMode & gpu_data::kOtherShadowsSoft) != 0;
    variant.specialization = {{2, otherShadowMode}, {3, soft ? spotFilter : gpu_data::kShadowFilterPcf5x5}};
    return variant;
}

const std::vector<gpu::SpecConstant> kGenericLitSpecialization = {
    {2, gpu_data::kOtherShadowsHard | gpu_data::kOtherShadowsSoft}, {3, gpu_data::kShadowFilterFromData}};

gpu_data::FrameData makeFrameData(const CameraView& view, const PackedLights& lights, const RenderRequest& request,
                                  const Settings& settings, bool screenSpaceShadows) {
    gpu_data::FrameData frame{};
    frame.clipFromWorld = view.clipFromWorld;
    frame.viewFromWorld = view.viewFromWorld;
    frame.worldFromClip = glm::inverse(view.clipFromWorld);
    frame.wsCameraPosition = glm::vec4(view.wsPosition, 1.0f);
    frame.viewport = glm::vec4(float(view.width), float(view.height), 1.0f / float(view.width), 1.0f / float(view.height));
    uint32_t mode = gpu_data::kOutputColor;
    if (request.output == OutputMode::ShadowAov) mode = gpu_data::kOutputShadowAov;
    if (request.output == OutputMode::CascadesAov) mode = gpu_data::kOutputCascadesAov;
    frame.counts = glm::uvec4(lights.directionalCount, lights.otherCount, mode, request.aovLight);
    frame.params = glm::vec4(settings.render.exposure, settings.render.ambient, screenSpaceShadows ? 1.0f : 0.0f, 0.0f);
    return frame;
}

// Copies `size` bytes into this frame's upload ring and returns where they are.
gpu::BufferSlice uploadFrameData(gpu::Device& device, const void* data, size_t size) {
    const gpu::FrameAllocation allocation = device.allocateFrameData(std::max<size_t>(size, 16));
    std::memcpy(allocation.mapped, data, size);
    return allocation.slice;
}

// An imported caller image, remembered so a swapchain's images are imported once each.
struct ImportedImage {
    uint64_t vkImage = 0;
    uint32_t width = 0, height = 0, format = 0;
    gpu::TextureHandle texture;
};
constexpr size_t kMaxImportedImages = 8;

// What a submitted frame still owes its caller once the GPU is done.
struct PendingFrame {
    uint64_t frameIndex = 0;
    FrameStats stats;
};

}  // namespace

struct Renderer::State {
    gpu::Device& device;
    Scene scene;
    RendererOptions options;
    GpuScene gpuScene;
    MainPass mainPass;
    ShadowCasterPass casterPass;
    ScreenSpaceShadowPass screenSpacePass;
    FrameTargets targets;
    gpu::SamplerHandle shadowSampler, pointSampler;
    gpu::TextureHandle noScreenShadows;  // bound at binding 9 when the screen-space resolve is off
    std::vector<ImportedImage> imported;
    std::deque<PendingFrame> pending;
    std::vector<FrameStats> completed;

    State(gpu::Device& d, Scene s, const RendererOptions& o)
        : device(d), scene(std::move(s)), options(o), gpuScene(d, scene), mainPass(d, gpuScene, o.warmup),
          casterPass(d, gpuScene, scene), screenSpacePass(d, mainPass), targets(d) {
        try {
            // Hardware 2x2 PCF: "fragment depth <= stored depth -> lit"; outside the atlas counts as lit.
            shadowSampler = d.createSampler({gpu::Filter::Linear, false, gpu::AddressMode::ClampToBorderWhite, true,
                                             gpu::CompareOp::LessOrEqual});
            pointSampler = d.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
            noScreenShadows = d.createTexture(
                {1, 1, gpu::Format::R32Float, gpu::kTextureSampled | gpu::kTextureColorTarget, 1, "no screen shadows"});
            gpu::CommandList commands = d.beginCommands();
            commands.transition(noScreenShadows, gpu::TextureState::Undefined, gpu::TextureState::ShaderRead);
            d.submitAndWait(commands);
            if (o.warmup == PipelineWarmup::Background) requestAllVariants();
        } catch (...) {
            destroyOwnObjects();  // the members' destructors run; this body's objects are ours to free
            throw;
        }
    }

    ~State() {
        // The passes and targets destroy their objects (deferred); wait so nothing is left pending.
        try {
            device.waitIdle();
        } catch (const Error&) {
        }
        destroyOwnObjects();
    }

    void destroyOwnObjects() {
        for (const ImportedImage& image : imported) device.destroy(image.texture);
        imported.clear();
        device.destroy(noScreenShadows);
        device.destroy(shadowSampler);
        device.destroy(pointSampler);
        noScreenShadows = {};
        shadowSampler = pointSampler = {};
    }

    // Every variant a setting can reach: the generic sets first (what frames fall back on), then the
    // specialized ones.
    void requestAllVariants() {
        for (gpu::Format format : {gpu::Format::RGBA8Srgb, gpu::Format::RGBA8Unorm}) {
            MainPassVariant generic = litVariant(format, 0, 0);
            generic.specialization = kGenericLitSpecialization;
            mainPass.request(generic);
        }
        mainPass.request(ScreenSpaceShadowPass::prepassVariant());
        for (gpu::Format format : {gpu::Format::RGBA8Srgb, gpu::Format::RGBA8Unorm})
            for (uint32_t mode = 0; mode < 4; ++mode)
                for (uint32_t filter = 0; filter < 4; ++filter) mainPass.request(litVariant(format, mode, filter));
    }

    gpu::TextureHandle importedTexture(const ExternalImage& target) {
        for (const ImportedImage& image : imported)
            if (image.vkImage == target.vkImage && image.width == target.width && image.height == target.height &&
                image.format == target.vkFormat)
                return image.texture;
        if (imported.size() >= kMaxImportedImages) {
            device.destroy(imported.front().texture);
            imported.erase(imported.begin());
        }
        gpu::ExternalTarget external{target.vkImage, target.vkFormat, target.width, target.height};
        imported.push_back({target.vkImage, target.width, target.height, target.vkFormat,
                            device.importTexture(external, "external target")});
        return imported.back().texture;
    }

    // What recording one frame needs; `stage` names the part being recorded.
    struct FrameRecording {
        const RenderRequest& request;
        const Settings& settings;
        const CameraView& view;
        const ShadowFrame& plan;
        const PackedLights& lights;
        const FrameTargetSizes& sizes;
        FrameStats& stats;
        Stopwatch& phase;
        const char* stage = "begin";
    };

    void checkRequest(const RenderRequest& request, const CameraView& view) const;
    uint64_t submit(const RenderRequest& request, const Settings& settings, const CameraView& view,
                    const ExternalImage* target, bool readback, bool captureAtlas);
    void record(gpu::CommandList& commands, FrameRecording& recording, const ExternalImage* target, bool readback,
                bool captureAtlas);
    void collectCompleted();
};

namespace {

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// A caller's CameraView (render(request, settings, view), submitFrame) is checked like a scene camera.
void checkCameraView(const CameraView& view) {
    if (!finite(view.clipFromWorld) || !finite(view.worldFromView) || !finite(view.viewFromWorld))
        throw Error("camera view: a matrix has a non-finite element");
    if (!(view.yfov > 0.0f && view.yfov < 3.14159265f)) throw Error("camera view: yfov must be in (0, pi)");
    if (!(std::isfinite(view.zNear) && view.zNear > 0.0f && view.zFar > view.zNear))
        throw Error("camera view: needs 0 < zNear < zFar");
}

gpu::ExternalTarget externalTargetOf(const ExternalImage& target) {
    return {target.vkImage,         target.vkFormat,        target.width,
            target.height,          target.vkInitialLayout, target.vkFinalLayout,
            target.vkWaitSemaphore, target.vkWaitStageMask, target.vkSignalSemaphore};
}

// The largest power of two that is <= limit (limit >= 1).
uint32_t powerOfTwoAtMost(uint32_t limit) {
    uint32_t size = 1;
    while (size <= limit / 2) size *= 2;
    return size;
}

// The shadow settings this device can hold: an atlas over the device's largest image side is made as
// large as it allows, with a warning.
ShadowSettings fitShadowSettings(const ShadowSettings& requested, uint32_t maxImageSize, std::vector<std::string>& warnings) {
    ShadowSettings fitted = requested;
    const uint32_t largest = powerOfTwoAtMost(maxImageSize);
    auto fit = [&](uint32_t& atlasSize, const char* key) {
        if (atlasSize <= largest) return;
        warnings.push_back(std::string(key) + " = " + std::to_string(atlasSize) + " is larger than the device's largest image (" +
                           std::to_string(maxImageSize) + "): using " + std::to_string(largest));
        atlasSize = largest;
    };
    fit(fitted.directional.atlasSize, "shadows.directional.atlasSize");
    fit(fitted.spot.atlasSize, "shadows.spot.atlasSize");
    return fitted;
}

}  // namespace

void Renderer::State::checkRequest(const RenderRequest& request, const CameraView& view) const {
    if (request.output != OutputMode::Color && request.aovLight >= scene.lights.size() && !scene.lights.empty())
        throw Error("--light " + std::to_string(request.aovLight) + " does not exist (the scene has " +
                    std::to_string(scene.lights.size()) + " lights)");
    const uint32_t limit = device.maxImageSize();
    if (request.width == 0 || request.height == 0 || request.width > limit || request.height > limit)
        throw Error("the output size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                    " is out of range (allowed 1.." + std::to_string(limit) + " per side on " + device.info().name + ")");
    if (view.width != request.width || view.height != request.height)
        throw Error("internal: the camera view is " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                    " but the request " + std::to_string(request.width) + "x" + std::to_string(request.height));
    checkCameraView(view);
}

uint64_t Renderer::State::submit(const RenderRequest& request, const Settings& settings, const CameraView& view,
                                 const ExternalImage* target, bool readback, bool captureAtlas) {
    validateSettings(settings);
    checkRequest(request, view);
    PendingFrame frame;
    FrameStats& stats = frame.stats;
    stats.warnings = gpuScene.warnings();
    const ShadowSettings shadows = fitShadowSettings(settings.shadows, device.maxImageSize(), stats.warnings);

    Stopwatch phase;
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, shadows);
    const PackedLights lights = packLights(scene, [&](uint32_t i) {
        const bool directional = scene.lights[i].type == LightType::Directional;
        const int32_t slot = (directional ? plan.directional.slotOfSceneLight : plan.other.slotOfSceneLight).at(i);
        return slot >= 0 ? uint32_t(slot) : kNoShadowSlot;
    });
    stats.cpu.culling = plan.stats.cullingMilliseconds;
    stats.cpu.plan = phase.milliseconds() - stats.cpu.culling;
    stats.warnings.insert(stats.warnings.end(), lights.warnings.begin(), lights.warnings.end());
    stats.warnings.insert(stats.warnings.end(), plan.other.warnings.begin(), plan.other.warnings.end());
    stats.shadowStatsJson = shadowStatsJson(plan);

    FrameTargetSizes sizes;
    sizes.directionalAtlas = plan.directional.atlas.tileCount > 0 ? plan.directional.atlas.atlasSize : 1u;
    sizes.otherAtlas = plan.other.atlas.tileCount > 0 ? plan.other.atlas.atlasSize : 1u;
    sizes.width = view.width;
    sizes.height = view.height;
    sizes.colorFormat = colorFormatOf(request.output);
    const uint64_t frameIndex = device.nextFrameIndex();
    const auto failed = [&](const char* stage, const Error& error) {
        return Error("frame " + std::to_string(frameIndex) + ", " + stage + ": " + error.what());
    };
    try {
        targets.ensure(sizes);
    } catch (const Error& error) {
        throw failed("render targets and shadow atlases", error);
    }

    phase.restart();
    gpu::CommandList commands = device.beginFrame();
    FrameRecording recording{request, settings, view, plan, lights, sizes, stats, phase};
    try {
        record(commands, recording, target, readback, captureAtlas);
    } catch (const Error& error) {
        device.abandonFrame(commands);
        throw failed(recording.stage, error);
    }
    const gpu::ExternalTarget sync = target ? externalTargetOf(*target) : gpu::ExternalTarget{};
    phase.restart();
    try {
        frame.frameIndex = device.submitFrame(commands, target ? &sync : nullptr);  // its errors name the frame
    } catch (const Error&) {
        device.abandonFrame(commands);
        throw;
    }
    gpuScene.updatesSubmitted();
    stats.cpu.submit = phase.milliseconds();
    stats.frameIndex = frame.frameIndex;
    pending.push_back(std::move(frame));
    collectCompleted();
    return pending.back().frameIndex;
}

// Records the frame's passes; `r.stage` names the one being recorded, for the error of a failure.
void Renderer::State::record(gpu::CommandList& commands, FrameRecording& r, const ExternalImage* target, bool readback,
                             bool captureAtlas) {
    r.stage = "scene updates";
    r.phase.restart();  // the wait for the slot's previous frame is not CPU work
    gpuScene.recordUpdates(commands, scene);
    r.stage = "frame data upload";
    const bool screenSpace = r.settings.shadows.screenSpace && !r.plan.directional.lights.empty();
    const gpu_data::FrameData frameData = makeFrameData(r.view, r.lights, r.request, r.settings, screenSpace);
    const gpu::BufferSlice frameSlice = uploadFrameData(device, &frameData, sizeof(frameData));
    const gpu::BufferSlice lightSlice =
        uploadFrameData(device, r.lights.lights.data(), r.lights.lights.size() * sizeof(gpu_data::LightData));
    const gpu::BufferSlice directionalSlice =
        uploadFrameData(device, &r.plan.directional.gpu, sizeof(r.plan.directional.gpu));
    const gpu::BufferSlice otherSlice = uploadFrameData(device, &r.plan.other.gpu, sizeof(r.plan.other.gpu));
    r.stats.cpu.upload = r.phase.milliseconds();
    static_assert(kMaxLights * sizeof(gpu_data::LightData) < (1u << 20));

    r.phase.restart();
    const std::vector<gpu::DescriptorWrite> casterWrites = sceneDescriptorWrites(gpuScene, frameSlice, lightSlice);
    r.stage = "shadows.directional";
    commands.beginTimer("shadows.directional");
    r.stats.atlases.push_back(casterPass.record(commands, scene, r.plan.directional.tiles, targets.directionalAtlas,
                                                r.sizes.directionalAtlas, casterWrites, "shadows.directional"));
    commands.endTimer();
    r.stage = "shadows.other";
    commands.beginTimer("shadows.other");
    r.stats.atlases.push_back(casterPass.record(commands, scene, r.plan.other.tiles, targets.otherAtlas,
                                                r.sizes.otherAtlas, casterWrites, "shadows.other"));
    commands.endTimer();

    MainPassInputs inputs;
    inputs.writes = casterWrites;
    inputs.writes.push_back({5, directionalSlice});
    inputs.writes.push_back({6, {}, targets.directionalAtlas, shadowSampler});
    inputs.writes.push_back({7, otherSlice});
    inputs.writes.push_back({8, {}, targets.otherAtlas, shadowSampler});
    inputs.writes.push_back({9, {}, noScreenShadows, pointSampler});
    r.stage = "screen-space shadows (depthPrepass, screenSpaceShadows)";
    if (screenSpace) inputs.writes.back().texture = screenSpacePass.record(commands, scene, r.view, inputs, 0);

    r.stage = "main";
    commands.beginTimer("main");
    commands.transition(targets.color, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    commands.transition(targets.depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    MainPass::Target main;
    main.color = targets.color;
    main.depth = targets.depth;
    main.width = r.view.width;
    main.height = r.view.height;
    main.variant = litVariant(r.sizes.colorFormat, r.plan.other.specializationMode, uint32_t(r.settings.shadows.spot.filter));
    main.genericSpecialization = kGenericLitSpecialization;
    // Shadow AOV: 1 (lit) where no geometry is; colour and cascades: black background.
    if (r.request.output == OutputMode::ShadowAov) std::fill(main.clearColor, main.clearColor + 4, 1.0f);
    mainPass.record(commands, scene, r.view, inputs, main);
    commands.endTimer();

    r.stage = "readback";
    if (readback) commands.copyTextureToBuffer(targets.color, gpu::TextureState::ColorTarget, targets.colorReadback());
    if (captureAtlas) {
        commands.copyTextureToBuffer(targets.directionalAtlas, gpu::TextureState::ShaderRead, targets.directionalReadback());
        commands.copyTextureToBuffer(targets.otherAtlas, gpu::TextureState::ShaderRead, targets.otherReadback());
    }
    if (target) {
        r.stage = "blit to the caller's image";
        commands.blitToExternal(targets.color, importedTexture(*target), externalTargetOf(*target));
    }
    r.stats.cpu.record = r.phase.milliseconds();
    r.stage = "submit";
}

void Renderer::State::collectCompleted() {
    for (gpu::CompletedFrame& done : device.takeCompletedFrames()) {
        while (!pending.empty() && pending.front().frameIndex < done.frameIndex) pending.pop_front();  // not ours
        if (pending.empty() || pending.front().frameIndex != done.frameIndex) continue;
        FrameStats stats = std::move(pending.front().stats);
        pending.pop_front();
        for (const gpu::PassTiming& t : done.timings) stats.gpuTimings.push_back({t.name, t.milliseconds});
        stats.submitToFenceMilliseconds = done.submitToFenceMilliseconds;
        completed.push_back(std::move(stats));
    }
}

namespace {

// The scene as the renderer takes it: checked first, so no bad index or value reaches the GPU.
Scene checkedScene(Scene scene) {
    validateScene(scene);
    return scene;
}

}  // namespace

Renderer::Renderer(Device& device, Scene scene, const RendererOptions& options) {
    Scene checked = checkedScene(std::move(scene));
    try {
        state_ = std::make_unique<State>(device.backend(), std::move(checked), options);
    } catch (const Error& error) {
        throw Error(std::string("putting the scene on the GPU: ") + error.what());
    }
}
Renderer::~Renderer() = default;

const Scene& Renderer::scene() const { return state_->scene; }

void Renderer::setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject) {
    setInstanceWorldTransform(state_->scene, instance, worldFromObject);
    state_->gpuScene.instanceChanged(instance);
}

void Renderer::setInstanceCastShadows(uint32_t instance, bool castShadows) {
    if (instance >= state_->scene.instances.size())
        throw Error("instance " + std::to_string(instance) + " does not exist (the scene has " +
                    std::to_string(state_->scene.instances.size()) + ")");
    state_->scene.instances[instance].castShadows = castShadows;  // read by the planner only
}

void Renderer::setLight(uint32_t light, const Light& value) { replaceLight(state_->scene, light, value); }

void Renderer::setMaterial(uint32_t material, const Material& value) {
    replaceMaterial(state_->scene, material, value);
    state_->gpuScene.materialChanged(material);
}

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings) {
    return render(request, settings, resolveCameraView(state_->scene, request.width, request.height));
}

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings, const CameraView& view) {
    State& s = *state_;
    const uint64_t frameIndex = s.submit(request, settings, view, nullptr, request.readback, request.captureAtlas);
    s.device.waitFrame(frameIndex);
    s.collectCompleted();
    RenderResult result;
    const auto found = std::find_if(s.completed.begin(), s.completed.end(),
                                    [&](const FrameStats& f) { return f.frameIndex == frameIndex; });
    if (found != s.completed.end()) {
        result.stats = std::move(*found);
        s.completed.erase(found);
    }
    const FrameTargetSizes& sizes = s.targets.sizes();
    if (request.readback)
        result.image = outputImageFromRgba(s.device.mappedPointer(s.targets.colorReadback()), sizes.width, sizes.height,
                                           request.output == OutputMode::ShadowAov ? 1 : 3);
    if (request.captureAtlas) {
        result.atlas = depthToGray(s.device.mappedPointer(s.targets.directionalReadback()), sizes.directionalAtlas);
        if (sizes.otherAtlas > 1)
            result.atlas = sideBySide(result.atlas,
                                      depthToGray(s.device.mappedPointer(s.targets.otherReadback()), sizes.otherAtlas));
    }
    return result;
}

uint64_t Renderer::submitFrame(const RenderRequest& request, const Settings& settings, const CameraView& view,
                               const ExternalImage* target) {
    return state_->submit(request, settings, view, target, false, false);
}

std::vector<FrameStats> Renderer::takeCompletedFrames() {
    state_->collectCompleted();
    std::vector<FrameStats> frames;
    frames.swap(state_->completed);
    return frames;
}

void Renderer::waitIdle() {
    state_->device.waitIdle();
    state_->collectCompleted();
}

uint32_t Renderer::pipelineBuildsPending() const { return state_->device.pipelineBuildsPending(); }

void Renderer::buildAllPipelines() {
    state_->requestAllVariants();
    state_->device.waitForPipelineBuilds();
}

}  // namespace penumbra
