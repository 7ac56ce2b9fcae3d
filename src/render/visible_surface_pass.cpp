#include "render/visible_surface_pass.h"

#include <algorithm>
#include <cstring>

#include "pass_bindings.h"
#include "core/error.h"
#include "render/frame_data.h"
#include "render/pass_layouts.h"
#include "render/screen_space_shadow_pass.h"

namespace penumbra {

gpu_data::VisibleBoundsData packVisibleBounds(const CameraView& view, std::span<const glm::mat4> lightRotations,
                                              float vsShadowDistance) {
    PENUMBRA_ASSERT(lightRotations.size() < gpu_data::kVisibleBoundsSpaces);
    gpu_data::VisibleBoundsData data{};
    data.worldFromClip = glm::inverse(view.clipFromWorld);  // as forEachSurfacePixel computes it
    for (size_t i = 0; i < lightRotations.size(); ++i) data.spaceFromWorld[i] = lightRotations[i];
    data.spaceFromWorld[lightRotations.size()] = glm::mat4(1.0f);  // the world: for a light not seen yet
    data.spaceCount = uint32_t(lightRotations.size()) + 1;
    const glm::mat4& v = view.viewFromWorld;  // vsDepth = -(viewFromWorld * p).z
    data.vsDepthRow = -glm::vec4(v[0][2], v[1][2], v[2][2], v[3][2]);
    data.width = view.width;
    data.height = view.height;
    data.vsBinNear = view.zNear;
    // The bins reach a quarter beyond the shadow distance: the last cascade's slice, which ends there,
    // and the bin the query adds beyond it hold no point from farther away (the last bin takes those).
    data.binsPerLogDepth = visibleBinsPerLogDepth(view.zNear, std::max(1.25f * vsShadowDistance, 2.0f * view.zNear));
    return data;
}

VisibleSurfacePass::VisibleSurfacePass(gpu::Device& device, const GpuScene& gpuScene, MainPass& mainPass)
    : device_(device), gpuScene_(gpuScene), mainPass_(mainPass) {
    frame_ = device.createBuffer(sizeof(gpu_data::FrameData), gpu::kBufferUniform, gpu::MemoryKind::HostVisible, nullptr,
                                 "visible-surface frame");
    gpu::ComputePipelineDesc desc;
    desc.shader = "visible_bounds.comp";
    desc.bindings = visibleBoundsBindings();
    desc.debugName = "visible bounds";
    bounds_ = device.createComputePipeline(desc);
    pointSampler_ = device.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
}

VisibleSurfacePass::~VisibleSurfacePass() {
    for (gpu::TextureHandle t : {normals_, depth_}) device_.destroy(t);
    for (gpu::BufferHandle b : {frame_, words_, readback_, boundsNowData_, boundsReadback_}) device_.destroy(b);
    device_.destroy(bounds_);
    device_.destroy(pointSampler_);
}

void VisibleSurfacePass::ensureTargets(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_ && depth_) return;
    for (gpu::TextureHandle t : {normals_, depth_}) device_.destroy(t);
    normals_ = device_.createTexture({width, height, gpu::Format::RGBA16Float, gpu::kTextureColorTarget, 1, "visible normals"});
    depth_ = device_.createTexture(
        {width, height, gpu::Format::D32Float, gpu::kTextureDepthTarget | gpu::kTextureTransferSrc, 1, "visible depth"});
    device_.destroy(readback_);
    readback_ = device_.createBuffer(uint64_t(width) * height * 4, gpu::kBufferTransferDst, gpu::MemoryKind::HostVisible,
                                     nullptr, "visible depth readback");
    width_ = width;
    height_ = height;
}

VisibleSurfaces VisibleSurfacePass::now(const Scene& scene, const CameraView& view) {
    ensureTargets(view.width, view.height);
    const gpu_data::FrameData frame = cameraFrameData(view);
    device_.writeBuffer(frame_, &frame, sizeof(frame));
    MainPassInputs inputs;
    const SceneWrites writes = sceneDescriptorWrites(gpuScene_, gpu::BufferSlice{frame_, 0, sizeof(frame)}, {});  // no lights: the prepass reads none
    inputs.writes.assign(writes.begin(), writes.end());
    MainPass::Target target;
    target.color = normals_;
    target.depth = depth_;
    target.variant = ScreenSpaceShadowPass::prepassVariant();  // alpha-tested like the lit pass
    target.width = view.width;
    target.height = view.height;
    target.passName = "visibleSurfaces";
    gpu::CommandList commands = device_.beginCommands();
    mainPass_.record(commands, scene, view, inputs, target);
    commands.pass("visibleSurfaces/readback", {gpu::use(depth_, gpu::Usage::TransferRead),
                                               gpu::use(readback_, gpu::Usage::TransferWrite)});
    commands.copyTextureToBuffer(depth_, readback_);
    commands.pass("visibleSurfaces/host", {gpu::use(readback_, gpu::Usage::HostRead)});
    device_.submitAndWait(commands);
    Image depth(view.width, view.height, 4);
    std::memcpy(depth.pixels.data(), device_.mappedPointer(readback_), depth.pixels.size());
    return visibleSurfacesFromDepth(depth, view);
}

void VisibleSurfacePass::recordReduction(gpu::CommandList& commands, gpu::TextureHandle depth,
                                         const gpu::BufferSlice& data) {
    if (!words_)
        words_ = device_.createBuffer(kReadbackBytes, gpu::kBufferStorage | gpu::kBufferTransferSrc | gpu::kBufferTransferDst,
                                      gpu::MemoryKind::DeviceLocal, nullptr, "visible bounds");
    const uint64_t half = kReadbackBytes / 2;
    commands.pass("visibleSurfaces/clear", {gpu::use(words_, gpu::Usage::TransferWrite)});
    commands.fillBuffer({words_, 0, half}, 0xffffffffu);  // the minima
    commands.fillBuffer({words_, half, half}, 0u);        // the maxima
    commands.pass("visibleSurfaces/bounds",
                  {gpu::use(depth, gpu::Usage::ComputeSampled), gpu::use(words_, gpu::Usage::ComputeWrite)});
    commands.bindPipeline(bounds_);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kVisibleBoundsBindingData, data},
                                           {gpu_data::kVisibleBoundsBindingDepth, {}, depth, pointSampler_},
                                           {gpu_data::kVisibleBoundsBindingWords, words_, {}, {}}};
    commands.pushDescriptors(writes);
    const gpu::TextureDesc& size = device_.textureDesc(depth);
    commands.dispatch((size.width + 7) / 8, (size.height + 7) / 8);
}

uint64_t VisibleSurfacePass::recordBounds(gpu::CommandList& commands, gpu::TextureHandle depth, const gpu::BufferSlice& data) {
    recordReduction(commands, depth, data);
    return device_.readBackAtFrameEnd(commands, {words_, 0, kReadbackBytes});
}

void VisibleSurfacePass::fromReadback(const uint8_t* bytes, const gpu_data::VisibleBoundsData& data, VisibleSurfaces& visible) {
    PENUMBRA_ASSERT(reinterpret_cast<uintptr_t>(bytes) % alignof(uint32_t) == 0);
    visibleSurfacesFromBoundsWords(reinterpret_cast<const uint32_t*>(bytes), data.vsBinNear, data.binsPerLogDepth,
                                   std::span(data.spaceFromWorld, data.spaceCount), visible);
}

VisibleSurfaces VisibleSurfacePass::boundsNow(gpu::TextureHandle depth, const CameraView& view,
                                              std::span<const glm::mat4> lightRotations, float vsShadowDistance) {
    const gpu::TextureDesc& desc = device_.textureDesc(depth);
    if (desc.width != view.width || desc.height != view.height || desc.format != gpu::Format::D32Float)
        throw Error("visible bounds: the depth texture '" + desc.debugName + "' is not the view's D32 depth");
    const gpu_data::VisibleBoundsData data = packVisibleBounds(view, lightRotations, vsShadowDistance);
    if (!boundsNowData_)
        boundsNowData_ = device_.createBuffer(sizeof(data), gpu::kBufferUniform, gpu::MemoryKind::HostVisible, nullptr,
                                              "visible bounds data");
    device_.writeBuffer(boundsNowData_, &data, sizeof(data));  // submitAndWait below: nothing reads it meanwhile
    if (!boundsReadback_)
        boundsReadback_ = device_.createBuffer(kReadbackBytes, gpu::kBufferTransferDst, gpu::MemoryKind::HostVisible,
                                               nullptr, "visible bounds readback");
    gpu::CommandList commands = device_.beginCommands();
    recordReduction(commands, depth, {boundsNowData_, 0, sizeof(data)});
    commands.pass("visibleSurfaces/readback", {gpu::use(words_, gpu::Usage::TransferRead),
                                               gpu::use(boundsReadback_, gpu::Usage::TransferWrite)});
    commands.copyBuffer({words_, 0, kReadbackBytes}, boundsReadback_, 0);
    commands.pass("visibleSurfaces/host", {gpu::use(boundsReadback_, gpu::Usage::HostRead)});
    device_.submitAndWait(commands);
    VisibleSurfaces visible;
    fromReadback(static_cast<const uint8_t*>(device_.mappedPointer(boundsReadback_)), data, visible);
    return visible;
}

}  // namespace penumbra
