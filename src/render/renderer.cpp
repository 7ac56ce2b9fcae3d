#include "penumbra/renderer.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "core/error.h"
#include "gpu/device_access.h"
#include "render/frame_setup.h"
#include "render/readback_images.h"
#include "render/renderer_state.h"
#include "scene/scene_edits.h"
#include "scene/scene_validation.h"

namespace penumbra {

Renderer::State::State(gpu::Device& d, Scene s, const RendererOptions& o)
    : device(d), scene(std::move(s)), options(o), gpuScene(d, scene), culling(d, gpuScene),
      mainPass(d, gpuScene, scene, o.warmup), casterPass(d, gpuScene), atlasCopy(d), screenSpacePass(d, mainPass),
      visiblePass(d, gpuScene, mainPass),
      computeRaster(d, gpuScene, o.rasterLargeQueue, o.rasterChunkQueue, o.rasterWorkQueue), virtualShadows(d, gpuScene, computeRaster),
      virtualFaces(d, gpuScene, computeRaster),
      lightClusters(d), rasterChoice(d.hasTimestamps(), d.info().name),
      mainViewChoice(d.hasTimestamps(), d.info().name, {"forward", "visibility", "main view"}), targets(d) {
    try {
        // The atlases and pools are read texel by texel (textureGather, texelFetch): the filters compare.
        pointSampler = d.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
        noScreenShadows = d.createTexture(
            {1, 1, gpu::Format::R32Float, gpu::kTextureSampled | gpu::kTextureColorTarget, 1, "no screen shadows"});
        if (o.warmup == PipelineWarmup::Background) requestAllVariants();
    } catch (...) {
        destroyOwnObjects();  // the members' destructors run; this body's objects are ours to free
        throw;
    }
}

Renderer::State::~State() {
    // The passes and targets destroy their objects (deferred); wait so nothing is left pending.
    try {
        device.waitIdle();
    } catch (const Error&) {
    }
    destroyOwnObjects();
}

void Renderer::State::destroyOwnObjects() {
    for (const ImportedImage& image : imported) device.destroy(image.texture);
    imported.clear();
    device.destroy(callerDepth.texture);
    callerDepth = ImportedImage{};
    device.destroy(noScreenShadows);
    device.destroy(pointSampler);
    noScreenShadows = {};
    pointSampler = {};
}

void Renderer::State::requestAllVariants() {
    for (gpu::Format format : {gpu::Format::RGBA8Srgb, gpu::Format::RGBA8Unorm}) {
        MainPassVariant generic = litVariant(format, {});
        generic.specialization = genericLitSpecialization();
        mainPass.request(generic);
    }
    mainPass.request(ScreenSpaceShadowPass::prepassVariant());
    // The directional kinds the scene's lights reach as they are (cascades or virtual maps by the setting,
    // pcss where a light has it); their filter is read from the data (prepareMainView), or the variants to
    // build would be five times as many. A light edited into another kind builds its variant on demand.
    using namespace gpu_data;
    bool directional = false, pcss = false;
    for (const Light& light : scene.lights) {
        directional = directional || (light.type == LightType::Directional && light.shadows != LightShadows::None);
        pcss = pcss || (light.type == LightType::Directional && light.shadows == LightShadows::Pcss);
    }
    std::vector<uint32_t> directionalModes = {0u};
    if (directional) {
        const uint32_t extra = pcss ? kDirectionalShadowsPcss : 0u;
        directionalModes = {kDirectionalShadowsCascades | extra, kDirectionalShadowsVirtual | extra};
    }
    for (uint32_t directionalMode : directionalModes)
        for (gpu::Format format : {gpu::Format::RGBA8Srgb, gpu::Format::RGBA8Unorm}) {
            for (uint32_t mode = 0; mode < 4; ++mode)
                for (uint32_t filter = 0; filter < 4; ++filter)
                    mainPass.request(litVariant(format, {directionalMode, kShadowFilterFromData, mode, filter}));
            mainPass.request(litVariant(format, {directionalMode, kShadowFilterFromData, kOtherShadowsVirtual, 0}));
        }
}

gpu::TextureHandle Renderer::State::importedTexture(const ExternalImage& target) {
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
        state_ = std::make_unique<State>(gpu::backend(device), std::move(checked), options);
    } catch (const Error& error) {
        throw Error(std::string("putting the scene on the GPU: ") + error.what());
    }
}
Renderer::~Renderer() {
    gpu::Device& device = state_->device;
    state_.reset();  // the passes and targets hand their objects to the device's deferred destruction
    try {
        device.waitIdle();  // nothing of this renderer's is in flight any more: destroyed now
        device.trimMemory();
    } catch (const Error&) {
        // A lost device: its objects go when the device does.
    }
}

const Scene& Renderer::scene() const { return state_->scene; }

void Renderer::State::setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject) {
    const bool exists = instance < scene.instances.size();
    const Aabb wsOldBounds = exists ? scene.instances[instance].wsBounds : Aabb{};
    if (exists) casterChanged(wsOldBounds);  // where it was
    setInstanceWorldTransform(scene, instance, worldFromObject);
    casterChanged(scene.instances[instance].wsBounds);  // and is now
    planWorkspace.instanceMoved(scene, instance, wsOldBounds);
    ++sceneVersion;
    gpuScene.instanceChanged(instance);
}

void Renderer::State::setInstanceCastShadows(uint32_t instance, bool castShadows) {
    if (instance >= scene.instances.size())
        throw Error("instance " + std::to_string(instance) + " does not exist (the scene has " +
                    std::to_string(scene.instances.size()) + ")");
    scene.instances[instance].castShadows = castShadows;
    casterChanged(scene.instances[instance].wsBounds);
    gpuScene.instanceChanged(instance);  // the GPU culling reads the flag
    ++sceneVersion;
    ++casterSetVersion;
}

void Renderer::State::setLight(uint32_t light, const Light& value) {
    replaceLight(scene, light, value);
    ++lightVersion;
}

void Renderer::State::setMaterial(uint32_t material, const Material& value) {
    replaceMaterial(scene, material, value);
    gpuScene.materialChanged(material);
    mainPass.materialsChanged(scene);  // its alpha mode may move its draws between opaque and blended
    invalidateVirtualMaps();  // its casters' cut-outs or cast flag may differ
    ++sceneVersion;
    ++casterSetVersion;
}

void Renderer::setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject) {
    state_->setInstanceTransform(instance, worldFromObject);
}
void Renderer::setInstanceCastShadows(uint32_t instance, bool castShadows) {
    state_->setInstanceCastShadows(instance, castShadows);
}
void Renderer::setLight(uint32_t light, const Light& value) { state_->setLight(light, value); }
void Renderer::setMaterial(uint32_t material, const Material& value) { state_->setMaterial(material, value); }

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings) {
    return render(request, settings, resolveCameraView(state_->scene, request.width, request.height));
}

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings, const CameraView& view) {
    State& s = *state_;
    RenderResult result;
    // A frame whose compute-raster queues overflowed is drawn again once they have grown (at most 3 times);
    // one that left virtual pages for later frames (more dirty pages than a frame draws) again while each
    // redraw draws some of them. With shadows.virtual.cache off every frame dirties every page again, so
    // the pages past the limit are never drawn: the result's warning says so.
    int redraws = 0;
    uint32_t deferred = 0, lastDeferred = std::numeric_limits<uint32_t>::max();
    for (;;) {
        const uint64_t frameIndex =
            s.submit(request, settings, view, nullptr, request.readback, request.captureAtlas, true);
        s.device.waitFrame(frameIndex);
        s.collectCompleted();
        for (size_t i = 0; i < s.completed.size(); ++i) {
            if (s.completed[i].frameIndex != frameIndex) continue;
            result.stats = std::move(s.completed[i]);
            s.completed.erase(i);
            break;
        }
        // A frame that overflowed the faces' pool is drawn again a step coarser (pool pressure).
        const bool coarser = std::exchange(s.facesWentCoarser, false);
        deferred = result.stats.virtualPages.deferred + result.stats.virtualFacePages.deferred;
        const bool progress = deferred > 0 && deferred < lastDeferred;
        lastDeferred = deferred;
        if ((result.stats.rasterDropped > 0 || coarser) && redraws < 3) {
            ++redraws;
            continue;
        }
        if (!progress) break;
    }
    if (deferred > 0)
        result.stats.warnings.push_back("virtual shadow maps: " + std::to_string(deferred) +
                                        " requested pages were not drawn (more dirty pages than a frame draws, "
                                        "shadows.virtual.pagesPerFrame, and every page dirty again each frame: "
                                        "shadows.virtual.cache off); a coarser level served them");
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
    return state_->submit(request, settings, view, target, false, false, false);
}

std::vector<FrameStats> Renderer::takeCompletedFrames() {
    std::vector<FrameStats> frames;
    takeCompletedFrames(frames);
    return frames;
}

void Renderer::takeCompletedFrames(std::vector<FrameStats>& frames) {
    State& s = *state_;
    s.collectCompleted();
    frames.resize(s.completed.size());
    // Swapped, not moved: the caller's previous elements go back to the renderer, whose next frames
    // reuse their storage.
    for (FrameStats& stats : frames) {
        std::swap(stats, s.completed.front());
        s.completed.popFront();
    }
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
