#pragma once
// The renderer's per-frame decisions that need no GPU: checks of a caller's camera, the shadow settings
// a device can hold, the lit pass variant of a frame, and the frame data block the shaders read.
#include <string>
#include <vector>

#include "gpu/device.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"
#include "render/frame_targets.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "scene_structs.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

gpu::Format colorFormatOf(OutputMode output);

// The shadow sampling a lit pass variant compiles (its specialization constants): the directional
// lights' kinds (kDirectionalShadows* bits: cascades, virtual maps, pcss) and filter, and the spot/point lights' kinds
// and filter (the specialization that stands for the _SHADOWS_HARD / _SHADOWS_SOFT keywords of Catlike
// Coding's "Spotlight Shadows"). The filter only matters when some light is soft, so the others share one
// variant.
struct LitShadowKinds {
    uint32_t directionalMode = 0;
    uint32_t directionalFilter = 0;  // kShadowFilter* or kShadowFilterFromData
    uint32_t otherMode = 0;
    uint32_t spotFilter = 0;
};
MainPassVariant litVariant(gpu::Format format, const LitShadowKinds& kinds);
void litVariant(gpu::Format format, const LitShadowKinds& kinds, MainPassVariant& variant);  // in place
// The specialization of the generic lit variant, which every frame can fall back on.
const std::vector<gpu::SpecConstant>& genericLitSpecialization();

gpu_data::FrameData makeFrameData(const CameraView& view, const PackedLights& lights, const RenderRequest& request,
                                  const Settings& settings, bool screenSpaceShadows);

// Scene light `light`'s slot in the plan (directional or spot/point), or kNoShadowSlot.
uint32_t shadowSlotOfSceneLight(const Scene& scene, const ShadowFrame& plan, uint32_t light);
// The scene's lights for the GPU, each shadowed one with its slot in the plan's atlases.
void packFrameLights(const Scene& scene, const ShadowFrame& plan, PackedLights& packed);  // replaced, storage reused

// The targets and atlases a frame of this plan, view and output draws into.
FrameTargetSizes frameTargetSizes(const ShadowFrame& plan, const CameraView& view, OutputMode output,
                                  const ShadowSettings& shadows);

// Copies `size` bytes into this frame's upload ring and returns where they are.
gpu::BufferSlice uploadFrameData(gpu::Device& device, const void* data, size_t size);

// A caller's CameraView (render(request, settings, view), submitFrame) is checked like a scene camera;
// throws Error naming what is wrong.
void checkCameraView(const CameraView& view);

// The shadow settings a device whose largest image side is maxImageSize can hold: a larger atlas is made
// as large as the device allows (the largest power of two), with a warning; shadows.directional.mode =
// auto and shadows.spot.mode = auto become the modes this device draws (resolveDirectionalShadowMode,
// resolveSpotShadowMode).
ShadowSettings fitShadowSettings(const ShadowSettings& requested, uint32_t maxImageSize, bool cpuDevice,
                                 std::vector<std::string>& warnings);
// shadows.directional.mode = auto as this device draws it: virtual on a GPU, cascades on a CPU device.
DirectionalShadowMode resolveDirectionalShadowMode(DirectionalShadowMode requested, bool cpuDevice);
// shadows.spot.mode = auto as this device draws it: virtual on a GPU, the spot atlas on a CPU device.
SpotShadowMode resolveSpotShadowMode(SpotShadowMode requested, bool cpuDevice);

}  // namespace penumbra
