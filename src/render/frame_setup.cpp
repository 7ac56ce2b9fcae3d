#include "render/frame_setup.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "render/frame_data.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

gpu::Format colorFormatOf(OutputMode output) {
    return output == OutputMode::Color ? gpu::Format::RGBA8Srgb : gpu::Format::RGBA8Unorm;
}

void litVariant(gpu::Format format, const LitShadowKinds& kinds, MainPassVariant& variant) {
    variant.colorFormat = format;
    variant.fragmentShader.assign(MainPassVariant{}.fragmentShader);
    variant.drawBlended = format == gpu::Format::RGBA8Srgb;  // the AOVs show the opaque surface only
    const bool soft = (kinds.otherMode & gpu_data::kOtherShadowsSoft) != 0;
    variant.specialization = {{2, kinds.otherMode},
                              {3, soft ? kinds.spotFilter : gpu_data::kShadowFilterPcf5x5},
                              {4, kinds.directionalMode},
                              {5, kinds.directionalMode != 0 ? kinds.directionalFilter : gpu_data::kShadowFilterPcf5x5}};
}

MainPassVariant litVariant(gpu::Format format, const LitShadowKinds& kinds) {
    MainPassVariant variant;
    litVariant(format, kinds, variant);
    return variant;
}

const std::vector<gpu::SpecConstant>& genericLitSpecialization() {
    static const std::vector<gpu::SpecConstant> generic = {
        {2, gpu_data::kOtherShadowsHard | gpu_data::kOtherShadowsSoft | gpu_data::kOtherShadowsVirtual},
        {3, gpu_data::kShadowFilterFromData},
        {4, gpu_data::kDirectionalShadowsAll},
        {5, gpu_data::kShadowFilterFromData}};
    return generic;
}

gpu_data::FrameData makeFrameData(const CameraView& view, const PackedLights& lights, const RenderRequest& request,
                                  const Settings& settings, bool screenSpaceShadows) {
    gpu_data::FrameData frame = cameraFrameData(view);
    uint32_t mode = gpu_data::kOutputColor;
    if (request.output == OutputMode::ShadowAov) mode = gpu_data::kOutputShadowAov;
    if (request.output == OutputMode::CascadesAov) mode = gpu_data::kOutputCascadesAov;
    frame.directionalLightCount = lights.directionalCount;
    frame.otherLightCount = lights.otherCount;
    frame.outputMode = mode;
    frame.aovLightIndex = request.aovLight;
    static_assert(uint32_t(ToneMapping::None) == gpu_data::kToneMapNone && uint32_t(ToneMapping::Neutral) == gpu_data::kToneMapNeutral &&
                  uint32_t(ToneMapping::Aces) == gpu_data::kToneMapAces);
    frame.exposure = settings.render.exposure;
    frame.ambient = settings.render.ambient;
    frame.screenSpaceShadows = screenSpaceShadows ? 1u : 0u;
    frame.toneMapping = uint32_t(settings.render.toneMapping);
    return frame;
}

uint32_t shadowSlotOfSceneLight(const Scene& scene, const ShadowFrame& plan, uint32_t light) {
    const bool directional = scene.lights[light].type == LightType::Directional;
    const int32_t slot = (directional ? plan.directional.slotOfSceneLight : plan.other.slotOfSceneLight).at(light);
    return slot >= 0 ? uint32_t(slot) : kNoShadowSlot;
}

void packFrameLights(const Scene& scene, const ShadowFrame& plan, PackedLights& packed) {
    packLights(scene, [&](uint32_t i) { return shadowSlotOfSceneLight(scene, plan, i); }, packed);
}

FrameTargetSizes frameTargetSizes(const ShadowFrame& plan, const CameraView& view, OutputMode output,
                                  const ShadowSettings& shadows) {
    FrameTargetSizes sizes;
    sizes.directionalAtlas = plan.directional.atlas.tileCount > 0 ? plan.directional.atlas.atlasSize : 1u;
    sizes.otherAtlas = plan.other.atlas.tileCount > 0 ? plan.other.atlas.atlasSize : 1u;
    sizes.width = view.width;
    sizes.height = view.height;
    sizes.colorFormat = colorFormatOf(output);
    sizes.computeRaster = shadows.raster != ShadowRaster::Hw;
    sizes.hardwareRaster = shadows.raster != ShadowRaster::Compute;
    return sizes;
}

gpu::BufferSlice uploadFrameData(gpu::Device& device, const void* data, size_t size) {
    const gpu::FrameAllocation allocation = device.allocateFrameData(std::max<size_t>(size, 16));
    std::memcpy(allocation.mapped, data, size);
    return allocation.slice;
}

namespace {

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// The largest power of two that is <= limit (limit >= 1).
uint32_t powerOfTwoAtMost(uint32_t limit) {
    uint32_t size = 1;
    while (size <= limit / 2) size *= 2;
    return size;
}

}  // namespace

void checkCameraView(const CameraView& view) {
    if (!finite(view.clipFromWorld) || !finite(view.worldFromView) || !finite(view.viewFromWorld))
        throw Error("camera view: a matrix has a non-finite element");
    if (!(view.yfov > 0.0f && view.yfov < 3.14159265f)) throw Error("camera view: yfov must be in (0, pi)");
    if (!(std::isfinite(view.zNear) && view.zNear > 0.0f && view.zFar > view.zNear))
        throw Error("camera view: needs 0 < zNear < zFar");
}

DirectionalShadowMode resolveDirectionalShadowMode(DirectionalShadowMode requested, bool cpuDevice) {
    if (requested != DirectionalShadowMode::Auto) return requested;
    // On a GPU the virtual maps win on both counts measured (docs/fidelity.md, docs/performance.md: fewer
    // misclassified pixels on every canonical scene, less shimmer, and a frame in motion 2x faster); a
    // CPU device marks and draws pages slower than it draws the atlas.
    return cpuDevice ? DirectionalShadowMode::Cascades : DirectionalShadowMode::Virtual;
}

SpotShadowMode resolveSpotShadowMode(SpotShadowMode requested, bool cpuDevice) {
    if (requested != SpotShadowMode::Auto) return requested;
    // On a GPU the virtual faces misclassify about half the atlas's pixels on every spot and point scene
    // (docs/fidelity.md) for about 0.15 ms a frame in motion (docs/performance.md); a CPU device pays far
    // more for their marking and page tables than for the atlas's cached tiles.
    return cpuDevice ? SpotShadowMode::Atlas : SpotShadowMode::Virtual;
}

ShadowSettings fitShadowSettings(const ShadowSettings& requested, uint32_t maxImageSize, bool cpuDevice,
                                 std::vector<std::string>& warnings) {
    ShadowSettings fitted = requested;
    fitted.directional.mode = resolveDirectionalShadowMode(requested.directional.mode, cpuDevice);
    fitted.spot.mode = resolveSpotShadowMode(requested.spot.mode, cpuDevice);
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

}  // namespace penumbra
