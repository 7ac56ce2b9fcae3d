#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <optional>

#include "core/error.h"
#include "core/stopwatch.h"
#include "render/compute_raster_pass.h"
#include "render/frame_data.h"
#include "render/frame_targets.h"
#include "render/gpu_scene.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "render/raster_choice.h"
#include "render/light_cluster_pass.h"
#include "render/light_clusters.h"
#include "render/readback_images.h"
#include "render/tile_cache.h"
#include "render/screen_space_shadow_pass.h"
#include "render/shadow_caster_pass.h"
#include "render/shadow_culling_pass.h"
#include "render/shadow_stats_json.h"
#include "render/visible_surface_pass.h"
#include "render/visibility_pass.h"
#include "scene/scene_edits.h"
#include "scene/scene_validation.h"
#include "scene_structs.h"
#include "cull_structs.h"
#include "shadows/cull_packing.h"
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
    gpu_data::FrameData frame = cameraFrameData(view);
    uint32_t mode = gpu_data::kOutputColor;
    if (request.output == OutputMode::ShadowAov) mode = gpu_data::kOutputShadowAov;
    if (request.output == OutputMode::CascadesAov) mode = gpu_data::kOutputCascadesAov;
    frame.counts = glm::uvec4(lights.directionalCount, lights.otherCount, mode, request.aovLight);
    static_assert(uint32_t(ToneMapping::Neutral) == gpu_data::kToneMapNeutral &&
                  uint32_t(ToneMapping::Aces) == gpu_data::kToneMapAces);
    frame.params = glm::vec4(settings.render.exposure, settings.render.ambient, screenSpaceShadows ? 1.0f : 0.0f,
                             float(settings.render.toneMapping));
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
    ShadowFrame plan;  // the stats JSON is written once the GPU's cull counts are back
    bool computeRaster = false;
    bool autoRaster = false;  // shadows.raster = auto and still measuring: its timings feed the choice
    bool clusterStats = false;     // the light cluster pass's LightClusterStats end the readback
    bool visibleReadback = false;  // the tight fit's depth subsample is in the readback, for later frames
    bool visibilityView = false;   // the main view came from the visibility buffer
    bool autoMainView = false;     // render.mainView = auto and still measuring: its main pass time feeds the choice
    bool viewStats = false;        // the visibility buffer's culling counts are in the readback (before the cluster stats)
    CameraView view;
    ShadowRaster rasterSetting = ShadowRaster::Auto;
};

double timerMilliseconds(const FrameStats& stats, const char* name) {
    for (const PassTiming& t : stats.gpuTimings)
        if (t.name == name) return t.milliseconds;
    return 0.0;
}

double shadowPassMilliseconds(const FrameStats& stats) {
    double total = 0.0;
    for (const PassTiming& t : stats.gpuTimings)
        if (t.name == "shadows.directional" || t.name == "shadows.other") total += t.milliseconds;
    return total;
}

// What the GPU culling pass reports per tile, turned into the frame's atlas stats and the
// planner stats JSON's casters per tile.
// The compute rasterizer's counters of both atlas passes, after the cull stats in the readback;
// `needed` gets the most large pieces and chunks one pass asked for.
void applyRasterCounters(FrameStats& stats, const ShadowFrame& plan, const std::vector<uint8_t>& readback,
                         glm::uvec2& needed) {
    const size_t offset = (plan.directional.tiles.size() + plan.other.tiles.size()) * sizeof(gpu_data::CullTileStats);
    for (size_t pass = 0; pass < 2; ++pass) {
        gpu_data::RasterCounters counters{};
        const size_t at = std::max<size_t>(offset, sizeof(gpu_data::CullTileStats)) + pass * sizeof(counters);
        if (readback.size() < at + sizeof(counters)) return;
        std::memcpy(&counters, readback.data() + at, sizeof(counters));
        stats.rasterLargeTriangles += counters.counts.x;
        stats.rasterChunks += counters.counts.y;
        stats.rasterDropped += counters.counts.z + counters.counts.w;
        stats.shadowMeshletsOutside += counters.meshlets.x;
        needed = glm::max(needed, glm::uvec2(counters.counts.x, counters.counts.y));
    }
    if (stats.rasterDropped > 0)
        stats.warnings.push_back("the compute rasterizer's queues were full: " + std::to_string(stats.rasterDropped) +
                                 " large pieces or chunks were not drawn in frame " + std::to_string(stats.frameIndex) +
                                 "; the queues grow for the next frames");
}

// The main view culling's counts: the two CullTileStats and the visibility rasterizer's meshlet counts,
// before the light cluster counts, if any.
void applyViewStats(FrameStats& stats, const std::vector<uint8_t>& readback, bool clusterStats) {
    gpu_data::CullTileStats lists[2]{};
    glm::uvec4 meshlets{0u};
    const size_t tail = sizeof(lists) + sizeof(meshlets) + (clusterStats ? sizeof(gpu_data::LightClusterStats) : 0);
    if (readback.size() < tail) return;
    std::memcpy(lists, readback.data() + readback.size() - tail, sizeof(lists));
    std::memcpy(&meshlets, readback.data() + readback.size() - tail + sizeof(lists), sizeof(meshlets));
    stats.viewInstancesEarly = lists[0].counts.y;
    stats.viewInstancesLate = lists[1].counts.y;
    stats.viewTriangles = uint64_t(lists[0].counts.z) + lists[1].counts.z;
    stats.viewMeshletsOutside = meshlets.x;
    stats.viewMeshletsFacingAway = meshlets.y;
}

// The light cluster pass's counts, the last bytes of the frame's readback.
void applyClusterStats(FrameStats& stats, const std::vector<uint8_t>& readback) {
    gpu_data::LightClusterStats counts{};
    if (readback.size() < sizeof(counts)) return;
    std::memcpy(&counts, readback.data() + readback.size() - sizeof(counts), sizeof(counts));
    stats.lightsPerClusterMean = double(counts.counts.x) / double(gpu_data::kClusterCount);
    stats.lightsPerClusterMax = counts.counts.y;
}

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

void applyCullStats(FrameStats& stats, const ShadowFrame& plan, const std::vector<uint8_t>& readback) {
    const size_t tileCount = plan.directional.tiles.size() + plan.other.tiles.size();
    std::vector<gpu_data::CullTileStats> tiles(tileCount);
    if (readback.size() >= tileCount * sizeof(gpu_data::CullTileStats) && tileCount > 0)
        std::memcpy(tiles.data(), readback.data(), tileCount * sizeof(gpu_data::CullTileStats));
    std::vector<CullTileCount> counts;
    for (size_t i = 0; i < tileCount; ++i) {
        AtlasDrawStats& atlas = stats.atlases[i < plan.directional.tiles.size() ? 0 : 1];
        atlas.draws += tiles[i].counts.x;
        atlas.triangles += tiles[i].counts.z;
        counts.push_back({tiles[i].counts.y, tiles[i].counts.z});
    }
    stats.shadowStatsJson = shadowStatsJson(plan, &counts);
}

}  // namespace

struct Renderer::State {
    gpu::Device& device;
    Scene scene;
    RendererOptions options;
    GpuScene gpuScene;
    ShadowCullingPass culling;
    MainPass mainPass;
    ShadowCasterPass casterPass;
    ScreenSpaceShadowPass screenSpacePass;
    VisibleSurfacePass visiblePass;
    ComputeRasterPass computeRaster;
    LightClusterPass lightClusters;
    RasterChoice rasterChoice;
    std::unique_ptr<VisibilityPass> visibility;  // made by the first visibility-buffer frame
    RasterChoice mainViewChoice;
    std::optional<VisibleSurfaces> latestVisible;  // the tight fit's reduction of the latest finished frame
    glm::uvec2 latestVisibleSize{0};
    glm::uvec2 rasterNeeded{0};  // the most large pieces / chunks a finished frame asked the compute rasterizer for
    TileCache directionalCache, otherCache;
    uint64_t directionalGenerationDrawn = ~0ull, otherGenerationDrawn = ~0ull;  // atlases the caches hold tiles of
    uint64_t sceneVersion = 0;   // bumped by every change to the casters (transforms, cast flags, materials)
    FrameTargets targets;
    gpu::SamplerHandle shadowSampler, pointSampler;
    gpu::TextureHandle noScreenShadows;  // bound at binding 9 when the screen-space resolve is off
    std::vector<ImportedImage> imported;
    std::deque<PendingFrame> pending;
    std::vector<FrameStats> completed;
    double lastGpuFrameEnd = 0.0;  // the latest finished frame's CompletedFrame::gpuEndMilliseconds

    State(gpu::Device& d, Scene s, const RendererOptions& o)
        : device(d), scene(std::move(s)), options(o), gpuScene(d, scene), culling(d, gpuScene),
          mainPass(d, gpuScene, o.warmup), casterPass(d, gpuScene), screenSpacePass(d, mainPass),
          visiblePass(d, gpuScene, mainPass),
          computeRaster(d, gpuScene, o.rasterLargeQueue, o.rasterChunkQueue), lightClusters(d), rasterChoice(d.hasTimestamps(), d.info().name),
          mainViewChoice(d.hasTimestamps(), d.info().name, {"forward", "visibility", "main view"}), targets(d) {
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

    // oneShot: the caller waits for this frame (render()): the tight fit reduces this very view's depth.
    void checkRequest(const RenderRequest& request, const CameraView& view) const;
    uint64_t submit(const RenderRequest& request, const Settings& settings, const CameraView& view,
                    const ExternalImage* target, bool readback, bool captureAtlas, bool oneShot);
    void collectCompleted();
};

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

uint64_t Renderer::State::submit(const RenderRequest& request, const Settings& requestedSettings,
                                 const CameraView& view, const ExternalImage* target, bool readback, bool captureAtlas,
                                 bool oneShot) {
    validateSettings(requestedSettings);
    checkRequest(request, view);
    PendingFrame frame;
    FrameStats& stats = frame.stats;
    stats.warnings = gpuScene.warnings();
    // The settings this device can hold (an atlas over its largest image is shrunk, with a warning).
    Settings fittedSettings = requestedSettings;
    fittedSettings.shadows = fitShadowSettings(requestedSettings.shadows, device.maxImageSize(), stats.warnings);
    const Settings& settings = fittedSettings;
    const bool visibilityOk = VisibilityPass::supported(device, gpuScene);
    if (settings.render.mainView == MainView::Visibility && !visibilityOk)
        throw Error(std::string("render.mainView = visibility is not available: ") +
                    (!device.hasBufferInt64Atomics() ? device.info().name + " has no 64-bit buffer atomics (or an embedder's device did not enable them)"
                                                     : "the scene has too many instances x triangles per mesh for 32-bit ids") +
                    "; use forward or auto");
    // auto keeps the forward pass on CPU devices, where the resolve is a fragment pass anyway.
    const bool autoCanChoose = visibilityOk && !device.info().isCpu;
    // The frames that may draw with the visibility buffer (auto: while measuring too).
    const bool visibilityWanted = settings.render.mainView == MainView::Visibility ||
                                  (autoCanChoose && settings.render.mainView == MainView::Auto);
    frame.visibilityView = settings.render.mainView == MainView::Auto
                               ? autoCanChoose && mainViewChoice.useCompute(ShadowRaster::Auto)
                               : visibilityWanted;
    frame.autoMainView = autoCanChoose && settings.render.mainView == MainView::Auto && !mainViewChoice.decided();
    stats.mainView = frame.visibilityView ? "visibility" : "forward";
    const uint64_t frameIndex = device.nextFrameIndex();
    const auto failed = [&](const char* stage, const Error& error) {
        return Error("frame " + std::to_string(frameIndex) + ", " + stage + ": " + error.what());
    };

    Stopwatch phase;
    PlanOptions planOptions;
    planOptions.cullCasters = false;  // the GPU culls (ShadowCullingPass)
    // The tight cascade fit's depth reduction (issue 13 item 8): this view's, waited for, when the
    // caller waits anyway or nothing earlier matches; else the latest finished frame's.
    const bool tight = settings.shadows.directional.fit == CascadeFit::Tight;
    const glm::uvec2 viewSize(view.width, view.height);
    std::optional<VisibleSurfaces> visible;
    if (tight && (oneShot || !latestVisible || latestVisibleSize != viewSize)) {
        try {
            visible = visiblePass.now(scene, view);
        } catch (const Error& error) {
            throw failed("the tight fit's visible surfaces", error);
        }
    }
    const VisibleSurfaces* planVisible = !tight ? nullptr : visible ? &*visible : &*latestVisible;
    frame.plan = ShadowPlanner::plan(scene, view, settings.shadows, planVisible, planOptions);
    const ShadowFrame& plan = frame.plan;
    const PackedLights lights = packLights(scene, [&](uint32_t i) {
        const bool directional = scene.lights[i].type == LightType::Directional;
        const int32_t slot = (directional ? plan.directional.slotOfSceneLight : plan.other.slotOfSceneLight).at(i);
        return slot >= 0 ? uint32_t(slot) : kNoShadowSlot;
    });
    stats.cpu.culling = plan.stats.cullingMilliseconds;
    stats.cpu.plan = phase.milliseconds() - stats.cpu.culling;
    stats.warnings.insert(stats.warnings.end(), lights.warnings.begin(), lights.warnings.end());
    stats.warnings.insert(stats.warnings.end(), plan.other.warnings.begin(), plan.other.warnings.end());

    FrameTargetSizes sizes;
    sizes.directionalAtlas = plan.directional.atlas.tileCount > 0 ? plan.directional.atlas.atlasSize : 1u;
    sizes.otherAtlas = plan.other.atlas.tileCount > 0 ? plan.other.atlas.atlasSize : 1u;
    sizes.width = view.width;
    sizes.height = view.height;
    sizes.colorFormat = colorFormatOf(request.output);
    sizes.computeRaster = settings.shadows.raster != ShadowRaster::Hw;
    try {
        targets.ensure(sizes);
    } catch (const Error& error) {
        throw failed("render targets and shadow atlases", error);
    }

    phase.restart();
    MainPassVariant litPass = litVariant(sizes.colorFormat, plan.other.specializationMode, uint32_t(settings.shadows.spot.filter));
    if (options.forceGenericVariants) litPass.specialization = kGenericLitSpecialization;
    // Also while auto still draws forward frames to measure: the visibility frames that follow then
    // make nothing (the steady state allocates no GPU object).
    if (visibilityWanted) {
        try {  // before the frame: its pipelines and buffers are made here, not while recording
            if (!visibility) visibility = std::make_unique<VisibilityPass>(device, gpuScene);
            visibility->prepare(litPass.specialization, sizes.colorFormat, view.width, view.height);
        } catch (const Error& error) {
            throw failed("the visibility-buffer main view", error);
        }
    }
    gpu::CommandList commands = device.beginFrame();
    // A failure from here to the submission drops the frame (the next one starts clean) and names the
    // part being recorded.
    const char* stage = "scene updates";
    try {
        phase.restart();  // the wait for the slot's previous frame is not CPU work
        stats.sceneBytesUploaded = gpuScene.recordUpdates(commands, scene);
        stage = "frame data upload";
        const bool screenSpace = settings.shadows.screenSpace && !plan.directional.lights.empty();
        const gpu_data::FrameData frameData = makeFrameData(view, lights, request, settings, screenSpace);
        const gpu::BufferSlice frameSlice = uploadFrameData(device, &frameData, sizeof(frameData));
        const gpu::BufferSlice lightSlice =
            uploadFrameData(device, lights.lights.data(), lights.lights.size() * sizeof(gpu_data::LightData));
        const bool clustered = settings.render.lightCulling == LightCulling::Clustered && lights.otherCount > 0;
        const gpu_data::LightClusterData clusterData =
            makeLightClusterData(view, scene.wsBounds, lights.directionalCount, lights.otherCount, clustered);
        const gpu::BufferSlice clusterSlice = uploadFrameData(device, &clusterData, sizeof(clusterData));
        const gpu::BufferSlice directionalSlice =
            uploadFrameData(device, &plan.directional.gpu, sizeof(plan.directional.gpu));
        const gpu::BufferSlice otherSlice = uploadFrameData(device, &plan.other.gpu, sizeof(plan.other.gpu));
        const uint32_t directionalTiles = uint32_t(plan.directional.tiles.size());
        const uint32_t cullTiles = directionalTiles + uint32_t(plan.other.tiles.size());
        frame.computeRaster = rasterChoice.useCompute(settings.shadows.raster);
        // Cached tiles: each atlas draws only the tiles that changed.
        std::vector<TileSignature> directionalSignatures, otherSignatures;
        for (const ShadowTile& tile : plan.directional.tiles) directionalSignatures.push_back(directionalTileSignature(tile, plan.directional));
        for (const ShadowTile& tile : plan.other.tiles) otherSignatures.push_back(otherTileSignature(tile));
        const bool freshDirectional = targets.directionalGeneration != directionalGenerationDrawn;
        const bool freshOther = targets.otherGeneration != otherGenerationDrawn;
        const std::vector<uint32_t> drawDirectional =
            directionalCache.tilesToDraw(directionalSignatures, targets.directionalGeneration, frame.computeRaster,
                                         sceneVersion, settings.shadows.cacheTiles);
        const std::vector<uint32_t> drawOther = otherCache.tilesToDraw(otherSignatures, targets.otherGeneration,
                                                                       frame.computeRaster, sceneVersion,
                                                                       settings.shadows.cacheTiles);
        directionalGenerationDrawn = targets.directionalGeneration;
        otherGenerationDrawn = targets.otherGeneration;
        stats.tilesRendered = uint32_t(drawDirectional.size() + drawOther.size());
        stats.tilesReused = directionalCache.reused() + otherCache.reused();
        gpu_data::CullFrame cullFrame = packCullFrame(plan, gpuScene.instanceCount(), gpuScene.meshSlotCount());
        cullFrame.camera = packCullCamera(view.clipFromWorld, view.width, view.height, settings.render.viewCulling);
        std::vector<uint32_t> rasterTiles = drawDirectional;
        for (uint32_t i : drawOther) rasterTiles.push_back(directionalTiles + i);
        packRasterTiles(cullFrame, rasterTiles);
        const gpu::BufferSlice cullSlice = uploadFrameData(device, &cullFrame, sizeof(cullFrame));
        stats.cpu.upload = phase.milliseconds();
        static_assert(kMaxLights * sizeof(gpu_data::LightData) < (1u << 20));

        phase.restart();
        const std::vector<gpu::DescriptorWrite> casterWrites = sceneDescriptorWrites(gpuScene, frameSlice, lightSlice);
        stage = "shadows.culling";
        commands.beginTimer("shadows.culling");
        culling.record(commands, cullSlice, cullTiles);
        commands.endTimer();
        frame.autoRaster = settings.shadows.raster == ShadowRaster::Auto && !rasterChoice.decided();
        frame.rasterSetting = settings.shadows.raster;
        // Twice what a frame asked for: a moving camera rarely needs another growth (each is one allocation).
        if (frame.computeRaster) computeRaster.reserve(2 * rasterNeeded.x, 2 * rasterNeeded.y);
        stats.shadowRaster = frame.computeRaster ? "compute" : "hw";
        auto drawAtlas = [&](const std::vector<ShadowTile>& tiles, const std::vector<uint32_t>& draw, bool fresh,
                             uint32_t firstTile, uint32_t listOffset, gpu::TextureHandle atlas, uint32_t size,
                             gpu::BufferHandle rasterDepth, const std::string& name) {
            if (frame.computeRaster) {
                ComputeRasterPass::AtlasTiles atlasTiles;
                atlasTiles.listOffset = listOffset;
                atlasTiles.freshAtlas = fresh;
                for (uint32_t i : draw)
                    atlasTiles.rects.push_back({int32_t(tiles[i].rect.offset.x), int32_t(tiles[i].rect.offset.y),
                                                tiles[i].rect.size, tiles[i].rect.size});
                computeRaster.record(commands, casterWrites, cullSlice, culling, atlasTiles, atlas, size, rasterDepth,
                                     settings.render.meshletCulling, "shadows." + name);
                device.readBackAtFrameEnd(commands, computeRaster.counters());
            } else {
                casterPass.record(commands, tiles, draw, fresh, firstTile, atlas, size, casterWrites, culling);
            }
        };
        device.readBackAtFrameEnd(commands, culling.tileStats(cullTiles));  // before the raster counters, see applyRasterCounters
        stage = "shadows.directional";
        commands.beginTimer("shadows.directional");
        drawAtlas(plan.directional.tiles, drawDirectional, freshDirectional, 0, 0, targets.directionalAtlas,
                  sizes.directionalAtlas, targets.directionalRasterDepth, "directional");
        commands.endTimer();
        stage = "shadows.other";
        commands.beginTimer("shadows.other");
        drawAtlas(plan.other.tiles, drawOther, freshOther, directionalTiles, uint32_t(drawDirectional.size()),
                  targets.otherAtlas, sizes.otherAtlas, targets.otherRasterDepth, "other");
        commands.endTimer();
        stats.atlases = {{"shadows.directional", directionalTiles, 0, 0}, {"shadows.other", cullTiles - directionalTiles, 0, 0}};

        stage = "light clusters";
        commands.beginTimer("lightClusters");
        lightClusters.record(commands, clusterSlice, lightSlice, clustered);
        commands.endTimer();
        frame.clusterStats = clustered;

        MainPassInputs inputs;
        inputs.writes = casterWrites;
        inputs.writes.push_back({gpu_data::kBindingLightClusters, clusterSlice});
        inputs.writes.push_back({gpu_data::kBindingClusterMasks, lightClusters.masks(), {}, {}});
        inputs.writes.push_back({5, directionalSlice});
        inputs.writes.push_back({6, {}, targets.directionalAtlas, shadowSampler});
        inputs.writes.push_back({7, otherSlice});
        inputs.writes.push_back({8, {}, targets.otherAtlas, shadowSampler});
        // 12, 13: the same atlases as raw depth (receiver-plane compare, blocker search; shaders/shadows.glsl).
        inputs.writes.push_back({12, {}, targets.directionalAtlas, pointSampler});
        inputs.writes.push_back({13, {}, targets.otherAtlas, pointSampler});
        inputs.writes.push_back({9, {}, noScreenShadows, pointSampler});  // last: the resolve's output replaces it
        stage = "screen-space shadows (depthPrepass, screenSpaceShadows)";
        if (screenSpace) inputs.writes.back().texture = screenSpacePass.record(commands, scene, view, inputs, 0);

        stage = frame.visibilityView ? "main (visibility buffer)" : "main";
        commands.beginTimer("main");
        MainPass::Target main;
        main.color = targets.color;
        main.depth = targets.depth;
        main.width = view.width;
        main.height = view.height;
        main.variant = litPass;
        main.genericSpecialization = kGenericLitSpecialization;
        // Shadow AOV: 1 (lit) where no geometry is; cascades: black; colour: black under the background.
        if (request.output == OutputMode::ShadowAov) std::fill(main.clearColor, main.clearColor + 4, 1.0f);
        main.background = request.output == OutputMode::Color && settings.render.background == Background::Gradient;
        if (frame.visibilityView) {
            VisibilityPass::Target opaque{targets.color, targets.depth, sizes.colorFormat, view.width, view.height, {},
                                          main.variant.specialization};
            std::copy(main.clearColor, main.clearColor + 4, opaque.clearColor);
            // Leaves both targets in their target states.
            visibility->record(commands, inputs.writes, opaque, culling, cullSlice, settings.render.viewCulling,
                               settings.render.meshletCulling);
            main.opaqueDone = true;
            stats.viewInstances = gpuScene.viewInstanceCount(scene);
        } else {
            commands.transition(targets.color, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
            commands.transition(targets.depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
        }
        mainPass.record(commands, scene, view, inputs, main);
        commands.endTimer();
        if (tight && !oneShot) {
            visiblePass.recordSubsample(commands, targets.depth, view);
            frame.visibleReadback = true;
            frame.view = view;
        }

        // Last in the readback (collectCompleted reads them from the end).
        frame.viewStats = frame.visibilityView;
        if (frame.viewStats) {
            device.readBackAtFrameEnd(commands, culling.viewStats());
            device.readBackAtFrameEnd(commands, visibility->meshletCounts());
        }
        if (clustered) device.readBackAtFrameEnd(commands, lightClusters.stats());
        stage = "readback";
        if (readback) commands.copyTextureToBuffer(targets.color, gpu::TextureState::ColorTarget, targets.colorReadback());
        if (captureAtlas) {
            commands.copyTextureToBuffer(targets.directionalAtlas, gpu::TextureState::ShaderRead, targets.directionalReadback());
            commands.copyTextureToBuffer(targets.otherAtlas, gpu::TextureState::ShaderRead, targets.otherReadback());
        }
        gpu::ExternalTarget sync;
        if (target) {
            sync = {target->vkImage, target->vkFormat, target->width, target->height, target->vkInitialLayout,
                    target->vkFinalLayout, target->vkWaitSemaphore, target->vkWaitStageMask, target->vkSignalSemaphore};
            commands.blitToExternal(targets.color, importedTexture(*target), sync);
        }
        stats.cpu.record = phase.milliseconds();

        phase.restart();
        stage = "submit";
        frame.frameIndex = device.submitFrame(commands, target ? &sync : nullptr);  // its errors name the frame
    } catch (const Error& error) {
        device.abandonFrame(commands);
        // The tile caches counted this frame's tiles as drawn: draw every tile of the next frame.
        directionalCache.invalidate();
        otherCache.invalidate();
        directionalGenerationDrawn = otherGenerationDrawn = ~0ull;
        if (std::string(stage) == "submit") throw;
        throw failed(stage, error);
    }
    gpuScene.updatesSubmitted();
    stats.cpu.submit = phase.milliseconds();
    stats.frameIndex = frame.frameIndex;
    pending.push_back(std::move(frame));
    collectCompleted();
    return pending.back().frameIndex;
}

void Renderer::State::collectCompleted() {
    for (gpu::CompletedFrame& done : device.takeCompletedFrames()) {
        while (!pending.empty() && pending.front().frameIndex < done.frameIndex) pending.pop_front();  // not ours
        if (pending.empty() || pending.front().frameIndex != done.frameIndex) continue;
        FrameStats stats = std::move(pending.front().stats);
        applyCullStats(stats, pending.front().plan, done.readback);
        if (pending.front().clusterStats) applyClusterStats(stats, done.readback);
        if (pending.front().viewStats) applyViewStats(stats, done.readback, pending.front().clusterStats);
        if (pending.front().computeRaster) applyRasterCounters(stats, pending.front().plan, done.readback, rasterNeeded);
        if (stats.rasterDropped > 0) {  // those tiles are incomplete: draw them all again
            directionalCache.invalidate();
            otherCache.invalidate();
        }
        const bool computeRasterFrame = pending.front().computeRaster, autoFrame = pending.front().autoRaster;
        const bool visibilityFrame = pending.front().visibilityView, autoMainView = pending.front().autoMainView;
        const ShadowRaster rasterSetting = pending.front().rasterSetting;
        if (pending.front().visibleReadback) {
            const PendingFrame& finished = pending.front();
            // After the cull stats (one per tile, at least one) and the compute rasterizer's two counters.
            const size_t tiles = finished.plan.directional.tiles.size() + finished.plan.other.tiles.size();
            const size_t offset = std::max<size_t>(tiles, 1) * sizeof(gpu_data::CullTileStats) +
                                  (finished.computeRaster ? 2 * sizeof(gpu_data::RasterCounters) : 0);
            if (done.readback.size() >= offset + VisibleSurfacePass::readbackBytes(finished.view)) {
                latestVisible = VisibleSurfacePass::fromReadback(done.readback.data() + offset, finished.view);
                latestVisibleSize = glm::uvec2(finished.view.width, finished.view.height);
            }
        }
        pending.pop_front();
        for (const gpu::PassTiming& t : done.timings) stats.gpuTimings.push_back({t.name, t.milliseconds});
        if (autoFrame) rasterChoice.measured(computeRasterFrame, shadowPassMilliseconds(stats));
        if (autoMainView) mainViewChoice.measured(visibilityFrame, timerMilliseconds(stats, "main"));
        stats.mainViewChoice = device.info().isCpu ? "forward (a CPU device: auto keeps the forward pass)"
                                                   : mainViewChoice.describe();
        stats.shadowRasterChoice = rasterSetting == ShadowRaster::Auto
                                       ? "auto: " + rasterChoice.describe()
                                       : std::string("shadows.raster = ") + shadowRasterName(rasterSetting);
        stats.submitToFenceMilliseconds = done.submitToFenceMilliseconds;
        stats.gpuFrameMilliseconds = done.gpuFrameMilliseconds;
        if (lastGpuFrameEnd > 0.0) stats.gpuFramePeriodMilliseconds = done.gpuEndMilliseconds - lastGpuFrameEnd;
        lastGpuFrameEnd = done.gpuEndMilliseconds;
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

void Renderer::setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject) {
    setInstanceWorldTransform(state_->scene, instance, worldFromObject);
    ++state_->sceneVersion;
    state_->gpuScene.instanceChanged(instance);
}

void Renderer::setInstanceCastShadows(uint32_t instance, bool castShadows) {
    if (instance >= state_->scene.instances.size())
        throw Error("instance " + std::to_string(instance) + " does not exist (the scene has " +
                    std::to_string(state_->scene.instances.size()) + ")");
    state_->scene.instances[instance].castShadows = castShadows;
    state_->gpuScene.instanceChanged(instance);  // the GPU culling reads the flag
    ++state_->sceneVersion;
}

void Renderer::setLight(uint32_t light, const Light& value) { replaceLight(state_->scene, light, value); }

void Renderer::setMaterial(uint32_t material, const Material& value) {
    replaceMaterial(state_->scene, material, value);
    state_->gpuScene.materialChanged(material);
    ++state_->sceneVersion;
}

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings) {
    return render(request, settings, resolveCameraView(state_->scene, request.width, request.height));
}

RenderResult Renderer::render(const RenderRequest& request, const Settings& settings, const CameraView& view) {
    State& s = *state_;
    RenderResult result;
    // A frame whose compute-raster queues overflowed is drawn again once they have grown.
    for (int attempt = 0; attempt < 4; ++attempt) {
        const uint64_t frameIndex =
            s.submit(request, settings, view, nullptr, request.readback, request.captureAtlas, true);
        s.device.waitFrame(frameIndex);
        s.collectCompleted();
        const auto found = std::find_if(s.completed.begin(), s.completed.end(),
                                        [&](const FrameStats& f) { return f.frameIndex == frameIndex; });
        if (found != s.completed.end()) {
            result.stats = std::move(*found);
            s.completed.erase(found);
        }
        if (result.stats.rasterDropped == 0) break;
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
    return state_->submit(request, settings, view, target, false, false, false);
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
