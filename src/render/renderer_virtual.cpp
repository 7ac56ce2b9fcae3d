// Renderer::State's steps between the lighting inputs and the main view (renderer_state.h): with
// shadows.directional.mode = virtual or shadows.spot.mode = virtual, the view's depth first (the
// visibility buffer's geometry, or the forward path's depth prepass), then every directional light's
// virtual shadow map chain from it and the spot and point lights' faces' chain; then the screen-space
// resolve (shadows.screenSpace), which samples the directional maps too.
#include <algorithm>

#include "render/renderer_state.h"

namespace penumbra {

const VisibilityPass::Target& Renderer::State::opaqueTargetFor(const FrameRecording& recording,
                                                               const MainPassVariant& litPass) {
    VisibilityPass::Target& opaque = opaqueTarget;  // copying into it reuses its list's storage
    opaque.color = targets.color;
    opaque.depth = targets.depth;
    opaque.colorFormat = recording.sizes.colorFormat;
    opaque.width = recording.view.width;
    opaque.height = recording.view.height;
    opaque.specialization = litPass.specialization;
    std::copy(recording.clearColor, recording.clearColor + 4, opaque.clearColor);
    opaque.backgroundGradient = recording.backgroundGradient;
    // Read after the resolve by the blended draws or the tight fit's depth reduction (recordVisibleBounds).
    opaque.depthRead = mainPass.drawsBlended(litPass) || tightCascadeFit(recording.settings);
    return opaque;
}

void Renderer::State::recordViewShadowInputs(FrameRecording& recording, MainPassInputs& inputs,
                                             const MainPassVariant& litPass) {
    const DirectionalShadowPlan& directional = recording.frame.plan.directional;
    // A settled kind (render/virtual_settling.h) keeps its pages and tables as they are: no pass, an empty timer.
    const bool directionalMaps = virtualShadows.active() && !directional.lights.empty() && !recording.frame.virtualSettled;
    const bool faces = virtualFaces.active() && !recording.frame.facesSettled;
    if (recording.frame.virtualSettled) virtualShadows.keepPages(directional);
    for (const auto& [settled, timer] : {std::pair{recording.frame.virtualSettled, "shadows.virtual"},
                                         std::pair{recording.frame.facesSettled, "shadows.virtualFaces"}}) {
        if (!settled) continue;
        recording.commands.beginTimer(timer);
        recording.commands.endTimer();
    }
    if (directionalMaps || faces) {
        gpu::CommandList& commands = recording.commands;
        const CameraView& view = recording.view;
        VirtualPageDepthSource depth;
        if (recording.callerDepth) {
            depth = VirtualPageDepthSource::texture(recording.callerDepth);  // a ShadowSystem caller's own
        } else if (recording.frame.visibilityView) {
            recording.stage = "main view depth (visibility buffer)";
            const RenderSettings& render = recording.settings.render;
            commands.beginTimer("mainDepth");
            visibility->recordGeometry(commands, inputs, opaqueTargetFor(recording, litPass), culling,
                                       recording.cullSlice, render.viewCulling, render.meshletCulling);
            commands.endTimer();
            recording.viewGeometryDone = true;
            depth = VirtualPageDepthSource::visibilityBuffer(visibility->visibilityBuffer(), view.width, view.height);
        } else {
            recording.stage = "depth prepass";
            depth = VirtualPageDepthSource::texture(prepassDepthOf(recording, inputs));
        }
        FrameReadbackLayout& readback = recording.frame.readback;
        if (directionalMaps) {
            recording.stage = "shadows.virtual";
            commands.beginTimer("shadows.virtual");
            virtualShadows.record(commands, depth, view, directional, scene.wsBounds,
                                  std::span(readback.rasterCounters).subspan(2, 4));
            commands.endTimer();
            const uint32_t maps = virtualShadows.mapsInUse(uint32_t(directional.lights.size()));
            readback.virtualLevelCount = virtualShadows.levelCount();
            for (uint32_t map = 0; map < maps; ++map) {
                readback.virtualPages[map] = device.readBackAtFrameEnd(commands, virtualShadows.stats(map));
                readback.virtualLevels[map] = device.readBackAtFrameEnd(commands, virtualShadows.levelStats(map));
            }
        }
        if (faces) {
            recording.stage = "shadows.virtualFaces";
            commands.beginTimer("shadows.virtualFaces");
            virtualFaces.record(commands, depth, view, readback.rasterCounters[6]);
            commands.endTimer();
            readback.virtualFacePages = device.readBackAtFrameEnd(commands, virtualFaces.stats());
            readback.virtualFaceMips = device.readBackAtFrameEnd(commands, virtualFaces.levelStats());
            readback.virtualFaceMipCount = virtualFaces.mipCount();
        }
    }
    recordScreenSpaceShadows(recording, inputs);
}

gpu::TextureHandle Renderer::State::prepassDepthOf(FrameRecording& recording, MainPassInputs& inputs) {
    if (!recording.prepassDepth)
        recording.prepassDepth = screenSpacePass.recordPrepass(recording.commands, scene, recording.view, inputs);
    return recording.prepassDepth;
}

void Renderer::State::recordScreenSpaceShadows(FrameRecording& recording, MainPassInputs& inputs) {
    if (!recording.screenSpace) return;
    recording.stage = "screen-space shadows (depthPrepass, screenSpaceShadows)";
    gpu::CommandList& commands = recording.commands;
    prepassDepthOf(recording, inputs);
    inputs.writes.back().texture = screenSpacePass.recordResolve(commands, recording.view, inputs, 0);
    inputs.sampled.back() = inputs.writes.back().texture;
}

}  // namespace penumbra
