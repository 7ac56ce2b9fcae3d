// Renderer::State's frame of shadows alone, for ShadowSystem (renderer_state.h): planned like a whole
// frame, then recorded into the caller's command buffer up to the shadow maps and virtual pages (with the
// view's depth where the virtual pages' marking or the tight cascade fit needs it), and handed over as
// the descriptors of <penumbra/shadows.glsl> in the state its shaders read them.
#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/stopwatch.h"
#include "penumbra/shadows/bindings.h"
#include "render/frame_data.h"
#include "render/frame_setup.h"
#include "render/renderer_state.h"
#include "pass_bindings.h"
#include "scene_structs.h"

namespace penumbra {

namespace {

static_assert(kShadowBindingCount == 12 && gpu_data::kLitBindingShadowView == gpu_data::kLitShadowBindingBase);

// The light table of penumbraShadow(light, ...): per scene light its kind and slot in the plan.
void packShadowLightTable(const Scene& scene, const ShadowFrame& plan, std::vector<gpu_data::ShadowLightSlot>& table) {
    table.resize(std::max<size_t>(scene.lights.size(), 1));
    table[0] = {gpu_data::kLightDirectional, gpu_data::kNoShadowSlot};  // the table is never empty
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const LightType type = scene.lights[i].type;
        table[i].type = type == LightType::Directional ? gpu_data::kLightDirectional
                        : type == LightType::Spot      ? gpu_data::kLightSpot
                                                       : gpu_data::kLightPoint;
        table[i].slot = shadowSlotOfSceneLight(scene, plan, i);
    }
}

}  // namespace

void Renderer::State::recordShadowFitDepth(FrameRecording& recording, MainPassInputs& inputs) {
    // The tight cascade fit reads the view's depth of the latest finished frame; with no main view of its
    // own, a shadow frame draws the depth prepass for it (virtual maps drew one already, or need none).
    const Settings& settings = recording.settings;
    if (!tightCascadeFit(settings)) return;
    recording.stage = "depth prepass (tight fit)";
    const gpu::TextureHandle depth = recording.callerDepth ? recording.callerDepth : prepassDepthOf(recording, inputs);
    recordVisibleBounds(recording, depth);
}

gpu::TextureHandle Renderer::State::importedDepth(const ShadowViewDepth& depth, const CameraView& view) {
    // The caller's own objects, wrapped, nothing made: the same handle values are the same objects.
    if (callerDepth.vkImage == depth.vkImage && callerDepth.vkImageView == depth.vkImageView &&
        callerDepth.width == view.width && callerDepth.height == view.height)
        return callerDepth.texture;
    device.destroy(callerDepth.texture);
    callerDepth = ImportedImage{};
    callerDepth.texture = device.importDepthTexture(depth.vkImage, depth.vkImageView, view.width, view.height, "caller depth");
    callerDepth.vkImage = depth.vkImage;
    callerDepth.vkImageView = depth.vkImageView;
    callerDepth.width = view.width;
    callerDepth.height = view.height;
    return callerDepth.texture;
}

// The light table and camera block of penumbraShadow, uploaded with the frame's other inputs (before any
// readback claims the ring).
void Renderer::State::uploadShadowHandOver(FrameRecording& recording) {
    using namespace gpu_data;
    packShadowLightTable(scene, recording.frame.plan, shadowLightTable);
    shadowLightTableSlice =
        uploadFrameData(device, shadowLightTable.data(), shadowLightTable.size() * sizeof(ShadowLightSlot));
    const ShadowViewData viewData = shadowViewData(recording.view, uint32_t(scene.lights.size()));
    shadowViewSlice = uploadFrameData(device, &viewData, sizeof(viewData));
}

void Renderer::State::handOverShadowBindings(FrameRecording& recording, const MainPassInputs& inputs,
                                             ShadowFrameWrites& writes) {
    using namespace gpu_data;
    uint32_t found = 0;
    for (const gpu::DescriptorWrite& write : inputs.writes) {
        if (write.binding < kLitShadowBindingBase || write.binding >= kLitShadowBindingBase + kShadowBindingCount) continue;
        gpu::DescriptorWrite& out = writes[write.binding - kLitShadowBindingBase];
        out = write;
        out.binding = write.binding - kLitShadowBindingBase;
        ++found;
    }
    // The lit pass binds no light table (it calls the slot-based functions): the frame's own goes there.
    if (found != kShadowBindingCount - 1) throw Error("internal: the lit pass's shadow bindings are incomplete");
    writes[kShadowBindingView] = gpu::DescriptorWrite(kShadowBindingView, shadowViewSlice);
    writes[kShadowBindingLights] = gpu::DescriptorWrite(kShadowBindingLights, shadowLightTableSlice);

    // Everything the caller's shaders read, made visible to its fragment and compute shaders, the
    // images in SHADER_READ_ONLY_OPTIMAL (docs/engine-integration.md, "Synchronisation").
    std::vector<gpu::ResourceUse>& uses = shadowHandOverUses;
    uses.clear();
    for (const gpu::DescriptorWrite& write : writes) {
        if (write.texture) {
            uses.push_back(gpu::use(write.texture, gpu::Usage::FragmentSampled));
            uses.push_back(gpu::use(write.texture, gpu::Usage::ComputeSampled));
        } else if (write.buffer && write.buffer.id != shadowLightTableSlice.buffer.id) {  // not the upload ring
            uses.push_back(gpu::use(write.buffer, gpu::Usage::GraphicsRead));
            uses.push_back(gpu::use(write.buffer, gpu::Usage::ComputeRead));
        }
    }
    recording.commands.pass("shadows handed over", uses);
}

gpu::Device::ExternalFrameEnd Renderer::State::recordShadowFrame(uint64_t vkCommandBuffer,
                                                                const Settings& requestedSettings,
                                                                const CameraView& view, const ShadowViewDepth* depth,
                                                                ShadowFrameWrites& writes) {
    validateSettings(requestedSettings);
    checkCameraView(view);
    const uint32_t limit = device.maxImageSize();
    if (view.width == 0 || view.height == 0 || view.width > limit || view.height > limit)
        throw Error("the view size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                    " is out of range (allowed 1.." + std::to_string(limit) + " per side on " + device.info().name + ")");
    PendingFrame& frame = pending.pushBack();  // recycled, as submit()'s
    try {
        return recordShadowFrameInto(frame, vkCommandBuffer, requestedSettings, view, depth, writes);
    } catch (...) {
        pending.popBack();
        throw;
    }
}

gpu::Device::ExternalFrameEnd Renderer::State::recordShadowFrameInto(PendingFrame& frame, uint64_t vkCommandBuffer,
                                                                    const Settings& requestedSettings,
                                                                    const CameraView& view,
                                                                    const ShadowViewDepth* viewDepth,
                                                                    ShadowFrameWrites& writes) {
    resetPendingFrame(frame);
    FrameStats& stats = frame.stats;
    Settings settings = requestedSettings;
    // The caller shades the view: no screen-space resolve, no light clusters.
    settings.shadows.screenSpace = false;
    settings.render.lightCulling = LightCulling::None;
    bool visibilityWanted = false;
    if (viewDepth) ++callerDepthFrames;  // never settled (renderer_state.h)
    const FrameTargetSizes sizes = planFrame(frame, settings, view, OutputMode::Color, false, true, visibilityWanted);
    const MainPassVariant& litPass = prepareMainView(settings, frame.plan, sizes, false);
    const uint64_t frameIndex = device.nextFrameIndex();
    RenderRequest request;
    request.width = view.width;
    request.height = view.height;

    const gpu::TextureHandle depth = viewDepth ? importedDepth(*viewDepth, view) : gpu::TextureHandle{};
    gpu::CommandList commands = device.beginExternalFrame(vkCommandBuffer);
    Stopwatch phase;  // after the wait for the slot, as submit()'s
    FrameRecording recording{commands, frame, settings, view, sizes, casterWrites};
    recording.callerDepth = depth;
    gpu::Device::ExternalFrameEnd end;
    try {
        // The caller's depth prepass wrote it before these commands (ShadowViewDepth's contract).
        if (depth) device.assumeWritten(depth, gpu::Usage::DepthTarget);
        stats.sceneBytesUploaded = editBytesUploaded + gpuScene.recordUpdates(commands, scene);
        uploadFrameInputs(recording, request, packedLights);
        uploadShadowHandOver(recording);
        const TilesToDraw& draw = chooseTilesToDraw(recording);
        stats.cpu.upload = phase.milliseconds();
        phase.restart();
        recordShadowAtlases(recording, draw);
        MainPassInputs& inputs = recordLightingInputs(recording);
        recordViewShadowInputs(recording, inputs, litPass);
        recordShadowFitDepth(recording, inputs);
        recording.stage = "hand-over";
        handOverShadowBindings(recording, inputs, writes);
        if (depth) commands.pass("caller depth returned", {gpu::use(depth, gpu::Usage::DepthTarget)});
        stats.cpu.record = phase.milliseconds();
        end = device.endExternalFrame(commands);
    } catch (const Error& error) {
        device.abandonFrame(commands);
        dropRecordedTiles();
        throw frameFailure(frameIndex, recording.stage, error);
    } catch (...) {
        device.abandonFrame(commands);
        dropRecordedTiles();
        throw;
    }
    gpuScene.updatesSubmitted();  // the caller submits the command buffer before the next frame
    frame.frameIndex = end.frameIndex;
    stats.frameIndex = end.frameIndex;
    collectCompleted();
    return end;
}

}  // namespace penumbra
