// Renderer::State's frame: checked, planned, recorded in steps (shadow atlases, lighting inputs, main
// view, outputs), submitted, and collected once the GPU is done (renderer_state.h).
#include <algorithm>
#include <array>
#include <span>
#include <string>

#include "core/error.h"
#include "core/stopwatch.h"
#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/frame_data.h"
#include "render/frame_setup.h"
#include "render/light_clusters.h"
#include "render/renderer_state.h"
#include "scene/scene_validation.h"
#include "scene_structs.h"
#include "shadows/cascades.h"
#include "shadows/cull_packing.h"

namespace penumbra {

namespace {

constexpr size_t kMaxLights = gpu_data::kMaxDirectionalLights + gpu_data::kMaxOtherLights;
static_assert(kMaxLights * sizeof(gpu_data::LightData) < (1u << 20));
// The two shadow atlas passes, as timed and reported (FrameStats::atlases): directional, then spot/point.
constexpr const char* kAtlasPassNames[2] = {"shadows.directional", "shadows.other"};

}  // namespace

Error frameFailure(uint64_t frameIndex, const std::string& stage, const Error& error) {
    return Error("frame " + std::to_string(frameIndex) + ", " + stage + ": " + error.what());
}

void Renderer::State::checkRequest(const RenderRequest& request, const CameraView& view) const {
    if (request.output != OutputMode::Color && request.aovLight >= scene.lights.size() && !scene.lights.empty())
        throw Error("light " + std::to_string(request.aovLight) + " does not exist (the scene has " +
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

bool Renderer::State::chooseMainView(const Settings& settings, PendingFrame& frame) const {
    const bool visibilityOk = VisibilityPass::supported(device, gpuScene);
    if (settings.render.mainView == MainView::Visibility && !visibilityOk)
        throw Error(std::string("render.mainView = visibility is not available: ") +
                    (!device.hasBufferInt64Atomics() ? device.info().name + " has no 64-bit buffer atomics (or an embedder's device did not enable them)"
                                                     : "the scene has too many instances x triangles per mesh for 32-bit ids") +
                    "; use forward or auto");
    // auto keeps the forward pass on CPU devices, where the resolve is a fragment pass anyway.
    const bool autoCanChoose = visibilityOk && !device.info().isCpu;
    const bool automatic = settings.render.mainView == MainView::Auto;
    // The frames that may draw with the visibility buffer (auto: while measuring too).
    const bool visibilityWanted = settings.render.mainView == MainView::Visibility || (autoCanChoose && automatic);
    frame.visibilityView = automatic ? autoCanChoose && mainViewChoice.useCompute(ShadowRaster::Auto) : visibilityWanted;
    frame.autoMainView = autoCanChoose && automatic && !mainViewChoice.decided();
    frame.stats.mainView = frame.visibilityView ? "visibility" : "forward";
    frame.mainViewSetting = settings.render.mainView;
    return visibilityWanted;
}

std::optional<VisibleSurfaces> Renderer::State::tightFitSurfacesNow(const Settings& settings, const CameraView& view,
                                                                   bool oneShot) {
    // The tight cascade fit's depth reduction (fit = tight): this view's, waited for, when the
    // caller waits anyway or nothing earlier matches; else the latest finished frame's (none here).
    if (!tightCascadeFit(settings)) return std::nullopt;
    if (!oneShot && latestVisible && latestVisibleSize == glm::uvec2(view.width, view.height)) return std::nullopt;
    // The depth pass draws the GPU's instances: the edits since the last frame go up first, or the fit
    // would see the scene as it was.
    editBytesUploaded = uploadSceneEditsNow();
    std::optional<VisibleSurfaces> surfaces = visiblePass.now(scene, view);
    if (!oneShot) {  // the next frames plan from it until their own reductions come back: one wait, not one per frame
        latestVisible = *surfaces;
        latestVisibleSize = glm::uvec2(view.width, view.height);
    }
    return surfaces;
}

uint64_t Renderer::State::uploadSceneEditsNow() {
    if (!gpuScene.hasPendingUpdates()) return 0;
    gpu::CommandList commands = device.beginFrame();
    uint64_t bytes = 0;
    try {
        bytes = gpuScene.recordUpdates(commands, scene);
    } catch (...) {
        device.abandonFrame(commands);  // the edits stay marked for the frame that follows
        throw;
    }
    device.submitFrame(commands);
    gpuScene.updatesSubmitted();
    return bytes;
}

void Renderer::State::planShadows(PendingFrame& frame, const Settings& settings, const CameraView& view,
                                  const std::optional<VisibleSurfaces>& visibleNow) {
    PlanOptions planOptions;
    planOptions.cullCasters = false;  // the GPU culls (ShadowCullingPass)
    planOptions.sceneVersion = casterSetVersion + 1;  // the caster set changes only with it (never 0); moves are reported
    // Virtual shadow maps fit no cascades: they plan with no visible surfaces.
    const bool tight = tightCascadeFit(settings);
    const VisibleSurfaces* planVisible = !tight ? nullptr : visibleNow ? &*visibleNow : &*latestVisible;
    ShadowPlanner::plan(scene, view, settings.shadows, planVisible, planOptions, frame.plan, planWorkspace);
}

const MainPassVariant& Renderer::State::prepareMainView(const Settings& settings, const ShadowFrame& plan,
                                                 const FrameTargetSizes& sizes, bool visibilityWanted) {
    MainPassVariant& litPass = litPassScratch;  // refilled in place: its lists keep their storage
    // A background warm-up builds the variants ahead with the directional filter read from the data
    // (requestAllVariants); on demand a variant compiles only the frame's directional filter too.
    const bool background = options.warmup == PipelineWarmup::Background;
    litVariant(sizes.colorFormat,
               {plan.directional.specializationMode,
                background ? gpu_data::kShadowFilterFromData : plan.directional.specializationFilter,
                plan.other.specializationMode, uint32_t(settings.shadows.spot.filter)},
               litPass);
    if (options.forceGenericVariants) litPass.specialization = genericLitSpecialization();
    // Also while auto still draws forward frames to measure: the visibility frames that follow then
    // make nothing (the steady state allocates no GPU object).
    if (visibilityWanted) {  // before the frame: its pipelines and buffers are made here, not while recording
        if (!visibility) visibility = std::make_unique<VisibilityPass>(device, gpuScene);
        visibility->prepare(litPass.specialization, sizes.colorFormat, sizes.width, sizes.height);
    }
    return litPass;
}

void Renderer::State::uploadFrameInputs(FrameRecording& recording, const RenderRequest& request,
                                        const PackedLights& lights) {
    const Settings& settings = recording.settings;
    const ShadowFrame& plan = recording.frame.plan;
    recording.stage = "frame data upload";
    recording.screenSpace = settings.shadows.screenSpace && !plan.directional.lights.empty();
    // Shadow AOV: 1 (lit) where no geometry is; cascades: black; colour: black under the background.
    const float clear = request.output == OutputMode::ShadowAov ? 1.0f : 0.0f;
    std::fill(recording.clearColor, recording.clearColor + 3, clear);
    recording.clearColor[3] = 1.0f;
    recording.backgroundGradient = request.output == OutputMode::Color && settings.render.background == Background::Gradient;
    const gpu_data::FrameData frameData = makeFrameData(recording.view, lights, request, settings, recording.screenSpace);
    recording.frameSlice = uploadFrameData(device, &frameData, sizeof(frameData));
    recording.lightSlice =
        uploadFrameData(device, lights.lights.data(), lights.lights.size() * sizeof(gpu_data::LightData));
    recording.clustered = settings.render.lightCulling == LightCulling::Clustered && lights.otherCount > 0;
    const gpu_data::LightClusterData clusterData = makeLightClusterData(
        recording.view, scene.wsBounds, lights.directionalCount, lights.otherCount, recording.clustered);
    recording.clusterSlice = uploadFrameData(device, &clusterData, sizeof(clusterData));
    // The lit passes call the shadow sampling per light of their own table, not penumbraShadow: no light table.
    const gpu_data::ShadowViewData shadowView = shadowViewData(recording.view, 0);
    recording.shadowViewSlice = uploadFrameData(device, &shadowView, sizeof(shadowView));
    recording.directionalSlice = uploadFrameData(device, &plan.directional.gpu, sizeof(plan.directional.gpu));
    recording.otherSlice = uploadFrameData(device, &plan.other.gpu, sizeof(plan.other.gpu));
    const SceneWrites writes = sceneDescriptorWrites(gpuScene, recording.frameSlice, recording.lightSlice);
    recording.casterWrites.assign(writes.begin(), writes.end());
    if (tightCascadeFit(settings)) uploadVisibleBoundsData(recording);
}

void Renderer::State::uploadVisibleBoundsData(FrameRecording& recording) {
    // Each directional light's bounds in its own space (the next frames' lights are most likely these).
    std::array<glm::mat4, gpu_data::kVisibleBoundsSpaces - 1> lightRotations;
    const std::vector<ReservedDirectionalLight>& lights = recording.frame.plan.directional.lights;
    const size_t count = std::min(lights.size(), lightRotations.size());
    for (size_t i = 0; i < count; ++i) lightRotations[i] = lightRotationFromWorld(lights[i].wsDirection);
    const float vsShadowDistance = shadowDistance(recording.view, recording.settings.shadows.maxDistance);
    gpu_data::VisibleBoundsData& data = recording.frame.visibleBounds;
    data = packVisibleBounds(recording.view, std::span(lightRotations.data(), count), vsShadowDistance);
    recording.visibleBoundsSlice = uploadFrameData(device, &data, sizeof(data));
}

const TilesToDraw& Renderer::State::chooseTilesToDraw(FrameRecording& recording) {
    const ShadowFrame& plan = recording.frame.plan;
    const ShadowSettings& shadows = recording.settings.shadows;
    const bool compute = recording.frame.computeRaster;
    directionalSignatures.clear();
    otherSignatures.clear();
    for (const ShadowTile& tile : plan.directional.tiles)
        directionalSignatures.push_back(directionalTileSignature(tile, plan.directional));
    for (const ShadowTile& tile : plan.other.tiles) otherSignatures.push_back(otherTileSignature(tile));
    TilesToDraw& draw = drawnTiles;
    draw.freshDirectional = targets.directionalGeneration != directionalGenerationDrawn;
    draw.freshOther = targets.otherGeneration != otherGenerationDrawn;
    directionalCache.tilesToDraw(directionalSignatures, targets.directionalGeneration, compute, sceneVersion,
                                 shadows.cacheTiles, draw.directional);
    otherCache.tilesToDraw(otherSignatures, targets.otherGeneration, compute, sceneVersion, shadows.cacheTiles, draw.other);
    directionalGenerationDrawn = targets.directionalGeneration;
    otherGenerationDrawn = targets.otherGeneration;
    FrameStats& stats = recording.frame.stats;
    stats.tilesRendered = uint32_t(draw.directional.size() + draw.other.size());
    stats.tilesReused = directionalCache.reused() + otherCache.reused();

    // The culling pass's frame and tile list: every planned tile is culled, the drawn ones rasterized
    // (one raster list per atlas pass).
    const CameraView& view = recording.view;
    gpu_data::CullFrame cullFrame = packCullFrame(plan, gpuScene.instanceCount(), gpuScene.meshSlotCount());
    cullFrame.camera = packCullCamera(view.clipFromWorld, view.width, view.height, recording.settings.render.viewCulling);
    recording.cullSlice = uploadFrameData(device, &cullFrame, sizeof(cullFrame));
    packCullTiles(plan, gpuScene.instanceCount(), gpuScene.meshSlotCount(), cullTileUpload);
    recording.cullTileSlice = uploadFrameData(device, &cullTileUpload, cullTileUpload.bytes());
    const uint32_t directionalTiles = uint32_t(plan.directional.tiles.size());
    packRasterTiles(plan.directional.tiles, draw.directional, 0, gpuScene.instanceCount(), rasterTileUploads[0]);
    packRasterTiles(plan.other.tiles, draw.other, directionalTiles, gpuScene.instanceCount(), rasterTileUploads[1]);
    for (size_t pass = 0; pass < 2; ++pass)
        recording.rasterListSlices[pass] = uploadFrameData(device, &rasterTileUploads[pass], rasterTileUploads[pass].bytes());
    return draw;
}

void Renderer::State::recordShadowAtlases(FrameRecording& recording, const TilesToDraw& draw) {
    gpu::CommandList& commands = recording.commands;
    PendingFrame& frame = recording.frame;
    const ShadowFrame& plan = frame.plan;
    const uint32_t directionalTiles = uint32_t(plan.directional.tiles.size());
    const uint32_t cullTiles = directionalTiles + uint32_t(plan.other.tiles.size());
    recording.stage = "shadows.culling";
    commands.beginTimer("shadows.culling");
    culling.record(commands, recording.cullSlice, recording.cullTileSlice);
    commands.endTimer();
    // The most a frame asked for (a queue more than half full doubles: few allocations in motion). The
    // virtual pages draw with the compute rasterizer whatever the atlases use.
    computeRaster.reserve(rasterNeeded.x, rasterNeeded.y, rasterNeeded.z);
    frame.readback.cullTiles = device.readBackAtFrameEnd(commands, culling.tileStats(cullTiles));
    auto drawAtlas = [&](size_t pass, const std::vector<ShadowTile>& tiles, const std::vector<uint32_t>& drawn, bool fresh,
                         uint32_t firstTile, gpu::TextureHandle atlas, uint32_t size, gpu::BufferHandle rasterDepth,
                         gpu::TextureHandle hardwareDepth) {
        const char* name = kAtlasPassNames[pass];
        recording.stage = name;
        commands.beginTimer(name);
        ComputeRasterPass::AtlasTiles& atlasTiles = atlasTilesScratch;  // its rects' storage is reused
        atlasTiles.freshAtlas = fresh;
        atlasTiles.rects.clear();
        for (uint32_t i : drawn) atlasTiles.rects.push_back(atlasRect(tiles[i]));
        if (frame.computeRaster) {
            const RasterTileLists lists{recording.cullSlice, recording.cullTileSlice, recording.rasterListSlices[pass]};
            computeRaster.record(commands, recording.casterWrites, lists, culling, atlasTiles, size, rasterDepth,
                                 frame.atlasRaster, name);
            frame.readback.rasterCounters[pass] = device.readBackAtFrameEnd(commands, computeRaster.counters());
            atlasCopy.copyFromBuffer(commands, commands.joinName(name, "/copy"), rasterDepth, atlas, size, atlasTiles.rects, fresh);
        } else {
            casterPass.record(commands, tiles, drawn, fresh, firstTile, hardwareDepth, size, recording.casterWrites, culling, name);
            atlasCopy.copyFromImage(commands, commands.joinName(name, "/copy"), hardwareDepth, atlas, size, atlasTiles.rects, fresh);
        }
        commands.endTimer();
    };
    const FrameTargetSizes& sizes = recording.sizes;
    drawAtlas(0, plan.directional.tiles, draw.directional, draw.freshDirectional, 0, targets.directionalAtlas,
              sizes.directionalAtlas, targets.directionalRasterDepth, targets.directionalHardwareDepth);
    drawAtlas(1, plan.other.tiles, draw.other, draw.freshOther, directionalTiles, targets.otherAtlas, sizes.otherAtlas,
              targets.otherRasterDepth, targets.otherHardwareDepth);
    std::vector<AtlasDrawStats>& atlases = frame.stats.atlases;  // recycled: names keep their storage
    atlases.resize(2);
    const uint32_t tilesOf[2] = {directionalTiles, cullTiles - directionalTiles};
    for (size_t pass = 0; pass < 2; ++pass) {
        atlases[pass].pass.assign(kAtlasPassNames[pass]);
        atlases[pass].tiles = tilesOf[pass];
        atlases[pass].draws = atlases[pass].triangles = 0;
    }
}

MainPassInputs& Renderer::State::recordLightingInputs(FrameRecording& recording) {
    gpu::CommandList& commands = recording.commands;
    recording.stage = "light clusters";
    commands.beginTimer("lightClusters");
    lightClusters.record(commands, recording.clusterSlice, recording.lightSlice, recording.clustered);
    commands.endTimer();
    if (recording.clustered) recording.frame.readback.lightClusters = device.readBackAtFrameEnd(commands, lightClusters.stats());

    MainPassInputs& inputs = mainInputs;  // refilled every frame: its lists keep their storage
    inputs.writes.assign(recording.casterWrites.begin(), recording.casterWrites.end());
    using namespace gpu_data;
    inputs.writes.push_back({kLitBindingLightClusters, recording.clusterSlice});
    inputs.writes.push_back({kLitBindingClusterMasks, lightClusters.masks(), {}, {}});
    inputs.writes.push_back({kLitBindingShadowView, recording.shadowViewSlice});
    inputs.writes.push_back({kLitBindingDirectionalShadows, recording.directionalSlice});
    // The atlases as raw depth, nearest: the filters compare textureGather's texels (penumbra/shadows/tent.glsl).
    inputs.writes.push_back({kLitBindingDirectionalAtlas, {}, targets.directionalAtlas, pointSampler});
    inputs.writes.push_back({kLitBindingOtherShadows, recording.otherSlice});
    inputs.writes.push_back({kLitBindingOtherAtlas, {}, targets.otherAtlas, pointSampler});
    inputs.sampled = {targets.directionalAtlas, targets.otherAtlas, noScreenShadows};
    virtualShadows.appendLitInputs(inputs, pointSampler);  // its pool goes before noScreenShadows
    virtualFaces.appendLitInputs(inputs, pointSampler);    // and so does this one
    inputs.writes.push_back({kLitBindingScreenSpaceShadows, {}, noScreenShadows, pointSampler});  // last: the resolve's output replaces it
    // noScreenShadows is never written: shaders read its binding only with shadows.screenSpace on.
    inputs.clusterMasks = lightClusters.masks();
    return inputs;
}

void Renderer::State::recordMainView(FrameRecording& recording, MainPassInputs& inputs,
                                     const MainPassVariant& litPass, bool oneShot) {
    gpu::CommandList& commands = recording.commands;
    PendingFrame& frame = recording.frame;
    const CameraView& view = recording.view;
    const RenderSettings& render = recording.settings.render;
    recording.stage = frame.visibilityView ? "main (visibility buffer)" : "main";
    commands.beginTimer("main");
    // The State's targets, every field set here: copying into them reuses their lists' storage.
    MainPass::Target& main = mainTarget;
    main.color = targets.color;
    main.depth = targets.depth;
    main.width = view.width;
    main.height = view.height;
    main.variant = litPass;
    main.genericSpecialization = genericLitSpecialization();
    std::copy(recording.clearColor, recording.clearColor + 4, main.clearColor);
    main.background = recording.backgroundGradient && !frame.visibilityView;  // the visibility resolve draws it
    main.opaqueDone = false;
    main.passName = MainPass::Target{}.passName;
    if (frame.visibilityView) {
        const VisibilityPass::Target& opaque = opaqueTargetFor(recording, litPass);
        // Writes the colour target, and the depth target where a later pass reads it (Target::depthRead).
        if (recording.viewGeometryDone) visibility->recordShading(commands, inputs, opaque);
        else visibility->record(commands, inputs, opaque, culling, recording.cullSlice, render.viewCulling,
                                render.meshletCulling);
        main.opaqueDone = true;
        frame.stats.viewInstances = gpuScene.viewInstanceCount(scene);
        frame.readback.viewLists = device.readBackAtFrameEnd(commands, culling.viewStats());
        frame.readback.viewMeshlets = device.readBackAtFrameEnd(commands, visibility->meshletCounts());
    }
    // After the visibility buffer's resolve only blended materials are left to draw.
    if (!main.opaqueDone || mainPass.drawsBlended(litPass)) mainPass.record(commands, scene, view, inputs, main);
    commands.endTimer();
    if (tightCascadeFit(recording.settings) && !oneShot)
        recordVisibleBounds(recording, targets.depth);
}

void Renderer::State::recordVisibleBounds(FrameRecording& recording, gpu::TextureHandle depth) {
    PENUMBRA_ASSERT(recording.visibleBoundsSlice.buffer);  // uploaded with the frame's inputs
    recording.frame.readback.visibleSurfaces =
        visiblePass.recordBounds(recording.commands, depth, recording.visibleBoundsSlice);
}

gpu::ExternalTarget Renderer::State::recordOutputs(FrameRecording& recording, const ExternalImage* target,
                                                   bool readback, bool captureAtlas) {
    gpu::CommandList& commands = recording.commands;
    recording.stage = "readback";
    using gpu::Usage;
    std::vector<std::pair<gpu::TextureHandle, gpu::BufferHandle>> copies;  // read by the host after the fence
    if (readback) copies.emplace_back(targets.color, targets.colorReadback());
    if (captureAtlas) {
        copies.emplace_back(targets.directionalAtlas, targets.directionalReadback());
        copies.emplace_back(targets.otherAtlas, targets.otherReadback());
    }
    if (!copies.empty()) {
        std::vector<gpu::ResourceUse> uses, hostReads;
        for (const auto& [texture, buffer] : copies) {
            uses.push_back(gpu::use(texture, Usage::TransferRead));
            uses.push_back(gpu::use(buffer, Usage::TransferWrite));
            hostReads.push_back(gpu::use(buffer, Usage::HostRead));
        }
        commands.pass("readback", uses);
        for (const auto& [texture, buffer] : copies) commands.copyTextureToBuffer(texture, buffer);
        commands.pass("readback/host", hostReads);
    }
    gpu::ExternalTarget sync;
    if (target) {
        commands.pass("external target", {gpu::use(targets.color, Usage::TransferRead)});
        sync = {target->vkImage, target->vkFormat, target->width, target->height, target->vkInitialLayout,
                target->vkFinalLayout, target->vkWaitSemaphore, target->vkWaitStageMask, target->vkSignalSemaphore};
        commands.blitToExternal(targets.color, importedTexture(*target), sync);
    }
    return sync;
}

uint64_t Renderer::State::submit(const RenderRequest& request, const Settings& requestedSettings,
                                 const CameraView& view, const ExternalImage* target, bool readback, bool captureAtlas,
                                 bool oneShot) {
    validateSettings(requestedSettings);
    checkRequest(request, view);
    PendingFrame& frame = pending.pushBack();  // recycled: what it held is reset or overwritten below
    try {
        return submitInto(frame, request, requestedSettings, view, target, readback, captureAtlas, oneShot);
    } catch (...) {
        pending.popBack();
        throw;
    }
}

FrameTargetSizes Renderer::State::planFrame(PendingFrame& frame, Settings& settings, const CameraView& view,
                                           OutputMode output, bool oneShot, bool shadowsOnly, bool& visibilityWanted) {
    FrameStats& stats = frame.stats;
    stats.warnings.assign(gpuScene.warnings().begin(), gpuScene.warnings().end());
    // The settings this device can hold (an atlas over its largest image is shrunk, with a warning) and
    // draws (shadows.directional.mode and shadows.spot.mode = auto resolved).
    settings.shadows = fitShadowSettings(settings.shadows, device.maxImageSize(), device.info().isCpu, stats.warnings);
    stats.directionalShadows = directionalShadowModeName(settings.shadows.directional.mode);
    stats.spotShadows = spotShadowModeName(settings.shadows.spot.mode);
    visibilityWanted = false;
    if (shadowsOnly) stats.mainView = "none";  // the caller draws it
    else visibilityWanted = chooseMainView(settings, frame);
    const uint64_t frameIndex = device.nextFrameIndex();

    Stopwatch phase;
    const ThreadStopwatch planThread;
    std::optional<VisibleSurfaces> visibleNow;
    editBytesUploaded = 0;
    try {
        visibleNow = tightFitSurfacesNow(settings, view, oneShot);
        stats.tightFitWaited = visibleNow.has_value();
    } catch (const Error& error) {
        throw frameFailure(frameIndex, "the tight fit's visible surfaces", error);
    }
    planShadows(frame, settings, view, visibleNow);
    const ShadowFrame& plan = frame.plan;
    const PackedLights& lights = packedLights;
    packFrameLights(scene, plan, packedLights);
    stats.cpu.culling = plan.stats.cullingMilliseconds;
    stats.cpu.plan = phase.milliseconds() - stats.cpu.culling;
    stats.cpu.thread = planThread.milliseconds();
    stats.warnings.insert(stats.warnings.end(), lights.warnings.begin(), lights.warnings.end());
    stats.warnings.insert(stats.warnings.end(), plan.other.warnings.begin(), plan.other.warnings.end());

    const ShadowRasterOptions raster = shadowRasterOptions(settings);
    virtualShadows.beginFrame(settings.shadows, uint32_t(plan.directional.lights.size()), raster, view, oneShot,
                              stats.warnings);
    stats.virtualPages.maps = virtualShadows.mapsInUse(uint32_t(plan.directional.lights.size()));
    stats.virtualPages.poolPages = virtualShadows.active() ? virtualShadows.poolPages() : 0u;
    stats.virtualPages.pagesPerFrame = virtualShadows.active() ? virtualShadows.pagesPerFrame() : 0u;
    virtualFaces.beginFrame(settings.shadows, plan.other, raster, view, stats.warnings);
    stats.virtualFacePages.maps = virtualFaces.faceCount();
    stats.virtualFacePages.poolPages = virtualFaces.poolPages();
    stats.virtualFacePages.pagesPerFrame = virtualFaces.pagesPerFrame();
    stats.virtualFacePages.lodBiasSteps = virtualFaces.poolPressureSteps();
    virtualSettling.beginFrame(frameIndex, {settings, view, sceneVersion + callerDepthFrames, lightVersion,
                                            virtualFaces.poolPressureSteps(),
                                            virtualShadows.moving(uint32_t(plan.directional.lights.size()))});
    frame.virtualSettled = virtualShadows.active() && virtualSettling.directionalSettled();
    frame.facesSettled = virtualFaces.active() && virtualSettling.facesSettled();
    frame.computeRaster = rasterChoice.useCompute(settings.shadows.raster);
    frame.atlasRaster = raster;
    if (!rasterChoice.computeForGood(settings.shadows.raster)) frame.atlasRaster.lodErrorTexels = 0.0f;
    if (frame.atlasRaster.lodErrorTexels != tilesLodErrorTexels) {  // the cached tiles hold other levels of detail
        directionalCache.invalidate();
        otherCache.invalidate();
        tilesLodErrorTexels = frame.atlasRaster.lodErrorTexels;
    }
    FrameTargetSizes sizes = frameTargetSizes(plan, view, output, settings.shadows);
    if (settings.shadows.raster == ShadowRaster::Auto && rasterChoice.decided()) {  // only the chosen path's depth
        sizes.computeRaster = frame.computeRaster;
        sizes.hardwareRaster = !frame.computeRaster;
    }
    try {
        targets.ensure(sizes);
    } catch (const Error& error) {
        throw frameFailure(frameIndex, "render targets and shadow atlases", error);
    }
    frame.autoRaster = settings.shadows.raster == ShadowRaster::Auto && !rasterChoice.decided();
    frame.rasterSetting = settings.shadows.raster;
    stats.shadowRaster = frame.computeRaster ? "compute" : "hw";
    return sizes;
}

void Renderer::State::dropRecordedTiles() {
    // The tile caches counted this frame's tiles as drawn: draw every tile of the next frame.
    directionalCache.invalidate();
    otherCache.invalidate();
    directionalGenerationDrawn = otherGenerationDrawn = ~0ull;
}

uint64_t Renderer::State::submitInto(PendingFrame& frame, const RenderRequest& request,
                                     const Settings& requestedSettings, const CameraView& view,
                                     const ExternalImage* target, bool readback, bool captureAtlas, bool oneShot) {
    resetPendingFrame(frame);
    FrameStats& stats = frame.stats;
    Settings settings = requestedSettings;
    bool visibilityWanted = false;
    const FrameTargetSizes sizes = planFrame(frame, settings, view, request.output, oneShot, false, visibilityWanted);
    const uint64_t frameIndex = device.nextFrameIndex();
    const MainPassVariant* litPass = nullptr;
    try {
        litPass = &prepareMainView(settings, frame.plan, sizes, visibilityWanted);
    } catch (const Error& error) {
        throw frameFailure(frameIndex, "the visibility-buffer main view", error);
    }
    const PackedLights& lights = packedLights;
    Stopwatch phase;
    ThreadStopwatch work;

    gpu::CommandList commands = device.beginFrame();
    // A failure from here to the submission drops the frame (the next one starts clean) and names the
    // part being recorded.
    FrameRecording recording{commands, frame, settings, view, sizes, casterWrites};
    try {
        phase.restart();  // the wait for the slot's previous frame is not CPU work
        work.restart();
        stats.sceneBytesUploaded = editBytesUploaded + gpuScene.recordUpdates(commands, scene);
        uploadFrameInputs(recording, request, lights);
        const TilesToDraw& draw = chooseTilesToDraw(recording);
        stats.cpu.upload = phase.milliseconds();

        phase.restart();
        recordShadowAtlases(recording, draw);
        MainPassInputs& inputs = recordLightingInputs(recording);
        recordViewShadowInputs(recording, inputs, *litPass);
        recordMainView(recording, inputs, *litPass, oneShot);
        gpu::ExternalTarget sync = recordOutputs(recording, target, readback, captureAtlas);
        stats.cpu.record = phase.milliseconds();

        phase.restart();
        recording.stage = "submit";
        frame.frameIndex = device.submitFrame(commands, target ? &sync : nullptr);  // its errors name the frame
    } catch (const Error& error) {
        device.abandonFrame(commands);
        dropRecordedTiles();
        if (std::string(recording.stage) == "submit") throw;
        throw frameFailure(frameIndex, recording.stage, error);
    }
    gpuScene.updatesSubmitted();
    stats.cpu.submit = phase.milliseconds();
    stats.cpu.thread += work.milliseconds();
    stats.frameIndex = frame.frameIndex;
    const uint64_t submitted = frame.frameIndex;
    collectCompleted();  // recycles only older slots: `frame` is the newest
    return submitted;
}

// A finished frame's virtual page counts: a skipped update repeats those of the frame that settled it;
// an update that found nothing to do settles its kind for the frames of the same inputs.
void Renderer::State::settleVirtualPages(PendingFrame& finished) {
    FrameStats& stats = finished.stats;
    const auto repeat = [](VirtualPageCounts& pages, const VirtualPageCounts& at) {
        pages.requested = pages.cached = at.requested;
        pages.resident = at.resident;
        pages.settled = true;
    };
    if (finished.virtualSettled) {
        repeat(stats.virtualPages, virtualSettling.directionalPages().pages);
        stats.virtualMaps = virtualSettling.directionalPages().levels;
    } else {
        virtualSettling.directionalFinished(finished.frameIndex, stats);
    }
    if (finished.facesSettled) {
        repeat(stats.virtualFacePages, virtualSettling.facePages().pages);
        stats.virtualFaceMips = virtualSettling.facePages().levels[0];
    } else {
        virtualSettling.facesFinished(finished.frameIndex, stats);
    }
}

// A frame the GPU has finished: its readback into its stats, its timings into the auto choices.
void Renderer::State::finishFrame(gpu::CompletedFrame& done, PendingFrame& finished) {
    FrameStats& stats = finished.stats;
    applyFrameReadback(stats, finished.plan, finished.readback, done.readback, rasterNeeded);
    settleVirtualPages(finished);
    facesWentCoarser = virtualFaces.notePoolLoad(stats.virtualFacePages) || facesWentCoarser;
    if (stats.rasterDropped > 0) {  // those tiles and pages are incomplete: draw them all again
        directionalCache.invalidate();
        otherCache.invalidate();
        invalidateVirtualMaps();
    }
    if (const uint8_t* words = readbackPiece(done.readback, finished.readback.visibleSurfaces,
                                             VisibleSurfacePass::kReadbackBytes)) {
        if (!latestVisible) latestVisible.emplace();
        const gpu_data::VisibleBoundsData& recorded = finished.visibleBounds;
        VisibleSurfacePass::fromReadback(words, recorded, *latestVisible);
        latestVisibleSize = glm::uvec2(recorded.width, recorded.height);
    }
    stats.gpuTimings.resize(done.timings.size());  // the elements' strings keep their storage
    for (size_t i = 0; i < done.timings.size(); ++i) {
        stats.gpuTimings[i].name.assign(done.timings[i].name);
        stats.gpuTimings[i].milliseconds = done.timings[i].milliseconds;
    }
    // Only frames that drew shadow tiles measure the rasterizers: a frame whose tiles were all cached
    // (a still camera) times two almost empty passes, which would make any path look fastest.
    if (finished.autoRaster && stats.tilesRendered > 0)
        rasterChoice.measured(finished.computeRaster, timedMilliseconds(stats, {kAtlasPassNames[0], kAtlasPassNames[1]}));
    if (finished.autoMainView) mainViewChoice.measured(finished.visibilityView, timedMilliseconds(stats, {"main"}));
    // Assigned piece by piece into the recycled strings (no temporary string, no allocation once warm).
    if (finished.mainViewSetting != MainView::Auto)
        stats.mainViewChoice.assign("render.mainView = ").append(mainViewName(finished.mainViewSetting));
    else if (device.info().isCpu)
        stats.mainViewChoice.assign("forward (a CPU device: auto keeps the forward pass)");
    else
        stats.mainViewChoice.assign(mainViewChoice.describe());
    const bool atlasTiles = !finished.plan.directional.tiles.empty() || !finished.plan.other.tiles.empty();
    if (finished.rasterSetting == ShadowRaster::Auto && !atlasTiles && !rasterChoice.decided())
        stats.shadowRasterChoice.assign("auto: no atlas tile to measure (virtual shadow maps draw with the compute rasterizer)");
    else if (finished.rasterSetting == ShadowRaster::Auto)
        stats.shadowRasterChoice.assign("auto: ").append(rasterChoice.describe());
    else
        stats.shadowRasterChoice.assign("shadows.raster = ").append(shadowRasterName(finished.rasterSetting));
    stats.submitToFenceMilliseconds = done.submitToFenceMilliseconds;
    stats.gpuFrameMilliseconds = done.gpuFrameMilliseconds;
    if (lastGpuFrameEnd > 0.0) stats.gpuFramePeriodMilliseconds = done.gpuEndMilliseconds - lastGpuFrameEnd;
    lastGpuFrameEnd = done.gpuEndMilliseconds;
}

void Renderer::State::collectCompleted() {
    for (gpu::CompletedFrame& done : device.completedFrames()) {
        while (!pending.empty() && pending.front().frameIndex < done.frameIndex) pending.popFront();  // not ours
        if (pending.empty() || pending.front().frameIndex != done.frameIndex) continue;
        const Stopwatch readbackTime;
        finishFrame(done, pending.front());
        pending.front().stats.cpu.readback = readbackTime.milliseconds();
        // Swapped, not moved: the pending slot takes the completed slot's storage for a later frame.
        std::swap(completed.pushBack(), pending.front().stats);
        pending.popFront();
    }
    device.releaseCompletedFrames();
}

// A recycled pending frame made new. The stats' lists that a frame refills element by element (pass
// timings, atlases, the plan's stats) and its strings keep their storage; the plan is replaced by the
// planner in place.
void Renderer::State::resetPendingFrame(PendingFrame& frame) {
    FrameStats& stats = frame.stats;
    std::vector<PassTiming> timings = std::move(stats.gpuTimings);
    std::vector<AtlasDrawStats> atlases = std::move(stats.atlases);
    std::vector<std::string> warnings = std::move(stats.warnings);
    ShadowPlanStats shadows = std::move(stats.shadows);
    std::string rasterChoice = std::move(stats.shadowRasterChoice), viewChoice = std::move(stats.mainViewChoice);
    stats = FrameStats{};
    stats.gpuTimings = std::move(timings);
    stats.atlases = std::move(atlases);
    stats.warnings = std::move(warnings);
    stats.warnings.clear();
    stats.shadows = std::move(shadows);
    stats.shadowRasterChoice = std::move(rasterChoice);
    stats.mainViewChoice = std::move(viewChoice);
    frame.frameIndex = 0;
    frame.readback = FrameReadbackLayout{};
    frame.computeRaster = frame.autoRaster = frame.visibilityView = frame.autoMainView = false;
    frame.virtualSettled = frame.facesSettled = false;
    frame.visibleBounds = gpu_data::VisibleBoundsData{};
    frame.rasterSetting = ShadowRaster::Auto;
    frame.mainViewSetting = MainView::Auto;
}

}  // namespace penumbra
