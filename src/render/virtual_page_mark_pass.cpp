#include "render/virtual_page_mark_pass.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <utility>
#include <vector>

#include "core/error.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

gpu_data::VirtualPageMarkData packVirtualPageMark(const VirtualClipmapConfig& config, const glm::mat4& lightRotation,
                                                  const CameraView& view, float marginTexels) {
    gpu_data::VirtualPageMarkData data{};
    // The same matrices and scalars as markVirtualPages computes them, so both sides round alike.
    data.worldFromClip = glm::inverse(view.clipFromWorld);
    data.viewFromWorld = view.viewFromWorld;
    data.lightFromWorld = lightRotation;
    data.lsCamera = lsClipmapCentre(lightRotation, view);
    data.marginTexels = marginTexels;
    data.wsFootprintPerDepth = wsFootprintPerDepth(view);
    data.width = view.width;
    data.height = view.height;
    data.pagesPerSide = pagesPerSide(config);
    data.levelCount = config.levelCount;
    data.firstLevelSize = config.firstLevelSize;
    data.resolution = config.resolution;
    data.requestWordCount = virtualPageRequestWords(config);
    return data;
}

namespace {

gpu::ComputePipelineDesc markPipeline(const char* shader, std::vector<gpu::BindingDesc> bindings, const char* name) {
    gpu::ComputePipelineDesc desc;
    desc.shader = shader;
    desc.bindings = std::move(bindings);
    desc.debugName = name;
    return desc;
}

}  // namespace

DepthSourcePipelines::DepthSourcePipelines(gpu::Device& device, const gpu::ComputePipelineDesc& texture,
                                           const gpu::ComputePipelineDesc& visibility)
    : device_(device) {
    texture_ = device.createComputePipeline(texture);
    try {
        visibility_ = device.createComputePipeline(visibility);
        pointSampler_ = device.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
    } catch (...) {
        device.destroy(texture_);  // the destructor does not run
        device.destroy(visibility_);
        throw;
    }
}

DepthSourcePipelines::~DepthSourcePipelines() {
    device_.destroy(texture_);
    device_.destroy(visibility_);
    device_.destroy(pointSampler_);
}

void DepthSourcePipelines::record(gpu::CommandList& commands, const VirtualPageDepthSource& source, const char* name,
                                  gpu::BufferHandle written, std::span<const gpu::DescriptorWrite> writes,
                                  uint32_t depthBinding, uint32_t visibilityBinding) {
    PENUMBRA_ASSERT(writes.size() <= kMaxWrites && (source.depth || source.visibility));
    std::array<gpu::DescriptorWrite, kMaxWrites + 1> all;  // no heap allocation per frame
    std::copy(writes.begin(), writes.end(), all.begin());
    uint32_t width = source.width, height = source.height;
    if (source.depth) {
        commands.pass(name, {gpu::use(source.depth, gpu::Usage::ComputeSampled), gpu::use(written, gpu::Usage::ComputeWrite)});
        commands.bindPipeline(texture_);
        all[writes.size()] = {depthBinding, {}, source.depth, pointSampler_};
        const gpu::TextureDesc& size = device_.textureDesc(source.depth);
        width = size.width;
        height = size.height;
    } else {
        commands.pass(name, {gpu::use(source.visibility, gpu::Usage::ComputeRead), gpu::use(written, gpu::Usage::ComputeWrite)});
        commands.bindPipeline(visibility_);
        all[writes.size()] = {visibilityBinding, source.visibility, {}, {}};
    }
    commands.pushDescriptors(std::span(all.data(), writes.size() + 1));
    commands.dispatch((width + 7) / 8, (height + 7) / 8);
}

VirtualPageMarkPass::VirtualPageMarkPass(gpu::Device& device)
    : device_(device),
      pipelines_(device, markPipeline("virtual_page_mark.comp", virtualPageMarkBindings(), "virtual page marking"),
                 markPipeline("virtual_page_mark_visibility.comp", virtualPageMarkVisibilityBindings(),
                              "virtual page marking (visibility buffer)")) {}

VirtualPageMarkPass::~VirtualPageMarkPass() {
    for (gpu::BufferHandle b : {requests_, readback_, markNowData_}) device_.destroy(b);
}

void VirtualPageMarkPass::ensureRequests(const VirtualClipmapConfig& config) {
    const uint64_t bytes = uint64_t(virtualPageRequestWords(config)) * 4;
    if (bytes == requestBytes_ && requests_) return;
    device_.destroy(requests_);
    device_.destroy(readback_);
    requests_ = device_.createBuffer(bytes, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal, nullptr, "virtual page requests");
    readback_ = device_.createBuffer(bytes, gpu::kBufferTransferDst, gpu::MemoryKind::HostVisible, nullptr,
                                     "virtual page requests readback");
    requestBytes_ = bytes;
}

void VirtualPageMarkPass::record(gpu::CommandList& commands, const VirtualPageDepthSource& source,
                                 const gpu::BufferSlice& mark, const VirtualClipmapConfig& config) {
    ensureRequests(config);
    commands.pass("virtualPages/clear", {gpu::use(requests_, gpu::Usage::TransferWrite)});
    commands.fillBuffer(requestWords(), 0u);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kPageMarkBindingFrame, mark},
                                           {gpu_data::kPageMarkBindingRequests, requests_, {}, {}}};
    pipelines_.record(commands, source, "virtualPages/mark", requests_, writes, gpu_data::kPageMarkBindingDepth,
                      gpu_data::kPageMarkBindingVisibility);
}

gpu::BufferSlice VirtualPageMarkPass::requestWords() const { return {requests_, 0, requestBytes_}; }

VirtualPageRequests VirtualPageMarkPass::fromReadback(const uint8_t* bytes, const VirtualClipmapConfig& config) {
    std::vector<uint32_t> words(virtualPageRequestWords(config));
    std::memcpy(words.data(), bytes, words.size() * 4);
    return VirtualPageRequests(config, words);
}

VirtualPageRequests VirtualPageMarkPass::markNow(gpu::TextureHandle depth, const CameraView& view,
                                                 const glm::mat4& lightRotation, const VirtualClipmapConfig& config,
                                                 float marginTexels) {
    const gpu::TextureDesc& desc = device_.textureDesc(depth);
    if (desc.width != view.width || desc.height != view.height || desc.format != gpu::Format::D32Float)
        throw Error("virtual page marking: the depth texture '" + desc.debugName + "' is not the view's D32 depth");
    const gpu_data::VirtualPageMarkData data = packVirtualPageMark(config, lightRotation, view, marginTexels);
    if (!markNowData_)
        markNowData_ = device_.createBuffer(sizeof(data), gpu::kBufferUniform, gpu::MemoryKind::HostVisible, nullptr,
                                            "virtual page marking data");
    device_.writeBuffer(markNowData_, &data, sizeof(data));  // submitAndWait below: nothing reads it meanwhile
    gpu::CommandList commands = device_.beginCommands();
    record(commands, VirtualPageDepthSource::texture(depth), {markNowData_, 0, sizeof(data)}, config);
    commands.pass("virtualPages/readback", {gpu::use(requests_, gpu::Usage::TransferRead),
                                            gpu::use(readback_, gpu::Usage::TransferWrite)});
    commands.copyBuffer(requestWords(), readback_, 0);
    commands.pass("virtualPages/host", {gpu::use(readback_, gpu::Usage::HostRead)});
    device_.submitAndWait(commands);
    return fromReadback(static_cast<const uint8_t*>(device_.mappedPointer(readback_)), config);
}

VirtualPageRequests VirtualPageMarkPass::markNow(const Image& depth, const CameraView& view, const glm::mat4& lightRotation,
                                                 const VirtualClipmapConfig& config, float marginTexels) {
    PENUMBRA_ASSERT(depth.width == view.width && depth.height == view.height && depth.channels == 4);
    const gpu::BufferHandle staging = device_.createBuffer(depth.pixels.size(), gpu::kBufferTransferSrc,
                                                           gpu::MemoryKind::HostVisible, depth.pixels.data(),
                                                           "virtual page marking depth upload");
    gpu::TextureHandle texture;
    const auto release = [&] {
        device_.destroy(texture);
        device_.destroy(staging);
    };
    try {
        texture = device_.createTexture(
            {depth.width, depth.height, gpu::Format::D32Float, gpu::kTextureSampled, 1, "virtual page marking depth"});
        gpu::CommandList commands = device_.beginCommands();
        commands.pass("virtualPages/upload", {gpu::discard(texture, gpu::Usage::TransferWrite)});
        commands.copyBufferToTexture(staging, texture);
        device_.submitAndWait(commands);
        VirtualPageRequests requests = markNow(texture, view, lightRotation, config, marginTexels);
        release();
        return requests;
    } catch (...) {
        release();
        throw;
    }
}

}  // namespace penumbra
