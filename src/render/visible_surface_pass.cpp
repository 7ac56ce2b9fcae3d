#include "render/visible_surface_pass.h"

#include <cstring>

#include "pass_bindings.h"
#include "render/frame_data.h"
#include "render/pass_layouts.h"
#include "render/screen_space_shadow_pass.h"

namespace penumbra {

namespace {

glm::uvec2 subsampleSize(const CameraView& view) {
    const uint32_t s = VisibleSurfacePass::kStride;
    return {(view.width + s - 1) / s, (view.height + s - 1) / s};
}

}  // namespace

VisibleSurfacePass::VisibleSurfacePass(gpu::Device& device, const GpuScene& gpuScene, MainPass& mainPass)
    : device_(device), gpuScene_(gpuScene), mainPass_(mainPass) {
    frame_ = device.createBuffer(sizeof(gpu_data::FrameData), gpu::kBufferUniform, gpu::MemoryKind::HostVisible, nullptr,
                                 "visible-surface frame");
    gpu::ComputePipelineDesc desc;
    desc.shader = "depth_subsample.comp";
    desc.bindings = depthSubsampleBindings();
    desc.pushConstantSize = sizeof(gpu_data::SubsampleConstants);
    desc.debugName = "depth subsample";
    subsample_ = device.createComputePipeline(desc);
    pointSampler_ = device.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
}

VisibleSurfacePass::~VisibleSurfacePass() {
    for (gpu::TextureHandle t : {normals_, depth_}) device_.destroy(t);
    for (gpu::BufferHandle b : {frame_, depths_, readback_}) device_.destroy(b);
    device_.destroy(subsample_);
    device_.destroy(pointSampler_);
}

void VisibleSurfacePass::ensureTargets(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_ && depth_) return;
    for (gpu::TextureHandle t : {normals_, depth_}) device_.destroy(t);
    device_.destroy(depths_);
    normals_ = device_.createTexture({width, height, gpu::Format::RGBA16Float, gpu::kTextureColorTarget, 1, "visible normals"});
    depth_ = device_.createTexture(
        {width, height, gpu::Format::D32Float, gpu::kTextureDepthTarget | gpu::kTextureTransferSrc, 1, "visible depth"});
    const uint32_t s = kStride;
    depths_ = device_.createBuffer(uint64_t((width + s - 1) / s) * ((height + s - 1) / s) * 4, gpu::kBufferStorage,
                                   gpu::MemoryKind::DeviceLocal, nullptr, "visible depth subsample");
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

uint64_t VisibleSurfacePass::recordSubsample(gpu::CommandList& commands, gpu::TextureHandle depth, const CameraView& view) {
    ensureTargets(view.width, view.height);
    const glm::uvec2 size = subsampleSize(view);
    commands.pass("visibleSurfaces/subsample",
                  {gpu::use(depth, gpu::Usage::ComputeSampled), gpu::use(depths_, gpu::Usage::ComputeWrite)});
    commands.bindPipeline(subsample_);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kSubsampleBindingDepth, {}, depth, pointSampler_},
                                                      {gpu_data::kSubsampleBindingDepths, depths_, {}, {}}};
    commands.pushDescriptors(writes);
    const gpu_data::SubsampleConstants constants{size.x, size.y, kStride};
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatch((size.x + 7) / 8, (size.y + 7) / 8);
    return device_.readBackAtFrameEnd(commands, {depths_, 0, readbackBytes(view)});
}

uint64_t VisibleSurfacePass::readbackBytes(const CameraView& view) {
    const glm::uvec2 size = subsampleSize(view);
    return uint64_t(size.x) * size.y * 4;
}

void VisibleSurfacePass::fromReadback(const uint8_t* bytes, const CameraView& view, VisibleSurfaces& visible) {
    const glm::uvec2 size = subsampleSize(view);
    visibleSurfacesFromDepths(bytes, size.x, size.y, view, kStride, visible);
}

}  // namespace penumbra
