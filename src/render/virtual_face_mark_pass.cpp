#include "render/virtual_face_mark_pass.h"

#include <cstring>

#include "core/error.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"
#include "shadows/virtual_page_marking.h"

namespace penumbra {

gpu_data::VirtualFaceMarkData packVirtualFaceMark(const VirtualFaceConfig& config, const CameraView& view,
                                                  uint32_t faceCount, uint32_t lightCount, float marginTexels,
                                                  float footprintScale) {
    gpu_data::VirtualFaceMarkData data{};
    // The same matrices and scalars as markVirtualFacePages computes them, so both sides round alike.
    data.worldFromClip = glm::inverse(view.clipFromWorld);
    data.viewFromWorld = view.viewFromWorld;
    data.wsFootprintPerDepth = wsFootprintPerDepth(view) * footprintScale;
    data.marginTexels = marginTexels;
    data.width = view.width;
    data.height = view.height;
    data.resolution = config.resolution;
    data.pageSize = config.pageSize;
    data.pagesPerSide = virtualFacePagesPerSide(config);
    data.mipCount = virtualFaceMipCount(config);
    data.faceCount = faceCount;
    data.lightCount = lightCount;
    data.requestWordCount = (virtualFaceTableLayout(config, faceCount).entryCount() + 31) / 32;
    return data;
}

gpu_data::VirtualFaceData packVirtualFace(const VirtualFace& face) {
    return {face.clipFromWorld, face.wsPosition, face.tanHalfFov};
}

namespace {

gpu::ComputePipelineDesc faceMarkPipeline(bool visibility) {
    gpu::ComputePipelineDesc desc;
    desc.shader = visibility ? "virtual_face_mark_visibility.comp" : "virtual_face_mark.comp";
    desc.bindings = virtualFaceMarkBindings(visibility);
    desc.debugName = visibility ? "virtual face marking (visibility buffer)" : "virtual face marking";
    return desc;
}

}  // namespace

VirtualFaceMarkPass::VirtualFaceMarkPass(gpu::Device& device)
    : device_(device), pipelines_(device, faceMarkPipeline(false), faceMarkPipeline(true)) {}

VirtualFaceMarkPass::~VirtualFaceMarkPass() { device_.destroy(requests_); }

void VirtualFaceMarkPass::ensureRequests(const VirtualPageTableLayout& layout) {
    const uint64_t bytes = uint64_t((layout.entryCount() + 31) / 32) * 4;
    if (bytes == requestBytes_ && requests_) return;
    device_.destroy(requests_);
    requests_ = device_.createBuffer(bytes, gpu::kBufferStorage | gpu::kBufferTransferSrc, gpu::MemoryKind::DeviceLocal,
                                     nullptr, "virtual face requests");
    requestBytes_ = bytes;
}

void VirtualFaceMarkPass::record(gpu::CommandList& commands, const VirtualPageDepthSource& source,
                                 const VirtualFaceMarkInputs& inputs, const VirtualPageTableLayout& layout) {
    ensureRequests(layout);
    commands.pass("virtualFaces/clear", {gpu::use(requests_, gpu::Usage::TransferWrite)});
    commands.fillBuffer(requestWords(), 0u);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kFaceMarkBindingFrame, inputs.mark},
                                           {gpu_data::kFaceMarkBindingRequests, requests_, {}, {}},
                                           {gpu_data::kFaceMarkBindingFaces, inputs.faces},
                                           {gpu_data::kFaceMarkBindingLights, inputs.lights}};
    pipelines_.record(commands, source, "virtualFaces/mark", requests_, writes, gpu_data::kFaceMarkBindingDepth,
                      gpu_data::kFaceMarkBindingVisibility);
}

namespace {

// A host-visible buffer holding `bytes` (at least 16), freed by its owner.
gpu::BufferHandle hostBuffer(gpu::Device& device, const void* data, size_t bytes, uint32_t usage, const char* name) {
    gpu::BufferHandle buffer = device.createBuffer(std::max<size_t>(bytes, 16), usage, gpu::MemoryKind::HostVisible,
                                                   nullptr, name);
    if (bytes > 0) device.writeBuffer(buffer, data, bytes);
    return buffer;
}

}  // namespace

std::vector<uint32_t> VirtualFaceMarkPass::markNow(const Image& depth, const CameraView& view, const VirtualFaceConfig& config,
                                                   std::span<const VirtualFace> faces, std::span<const VirtualFaceLight> lights,
                                                   float marginTexels, float footprintScale) {
    PENUMBRA_ASSERT(depth.width == view.width && depth.height == view.height && depth.channels == 4 && !faces.empty());
    const VirtualPageTableLayout layout = virtualFaceTableLayout(config, uint32_t(faces.size()));
    const gpu_data::VirtualFaceMarkData mark =
        packVirtualFaceMark(config, view, uint32_t(faces.size()), uint32_t(lights.size()), marginTexels, footprintScale);
    std::vector<gpu_data::VirtualFaceData> faceData;
    for (const VirtualFace& face : faces) faceData.push_back(packVirtualFace(face));
    std::vector<gpu_data::VirtualFaceLightData> lightData;
    for (const VirtualFaceLight& light : lights) lightData.push_back({light.firstFace, light.point ? 1u : 0u, 0u, 0u});
    std::vector<gpu::BufferHandle> buffers;
    gpu::TextureHandle texture;
    const auto release = [&] {
        device_.destroy(texture);
        for (gpu::BufferHandle b : buffers) device_.destroy(b);
    };
    try {
        buffers.push_back(hostBuffer(device_, &mark, sizeof(mark), gpu::kBufferUniform, "virtual face marking data"));
        buffers.push_back(hostBuffer(device_, faceData.data(), faceData.size() * sizeof(faceData[0]), gpu::kBufferStorage,
                                     "virtual faces"));
        buffers.push_back(hostBuffer(device_, lightData.data(), lightData.size() * sizeof(lightData[0]),
                                     gpu::kBufferStorage, "virtual face lights"));
        buffers.push_back(hostBuffer(device_, depth.pixels.data(), depth.pixels.size(), gpu::kBufferTransferSrc,
                                     "virtual face marking depth upload"));
        ensureRequests(layout);
        buffers.push_back(device_.createBuffer(requestBytes_, gpu::kBufferTransferDst, gpu::MemoryKind::HostVisible,
                                               nullptr, "virtual face requests readback"));
        texture = device_.createTexture(
            {depth.width, depth.height, gpu::Format::D32Float, gpu::kTextureSampled, 1, "virtual face marking depth"});
        gpu::CommandList commands = device_.beginCommands();
        commands.pass("virtualFaces/upload", {gpu::discard(texture, gpu::Usage::TransferWrite)});
        commands.copyBufferToTexture(buffers[3], texture);
        record(commands, VirtualPageDepthSource::texture(texture),
               {{buffers[0], 0, sizeof(mark)},
                {buffers[1], 0, faceData.size() * sizeof(faceData[0])},
                {buffers[2], 0, std::max<size_t>(lightData.size() * sizeof(lightData[0]), 16)}},
               layout);
        commands.pass("virtualFaces/readback", {gpu::use(requests_, gpu::Usage::TransferRead),
                                                gpu::use(buffers[4], gpu::Usage::TransferWrite)});
        commands.copyBuffer(requestWords(), buffers[4], 0);
        commands.pass("virtualFaces/host", {gpu::use(buffers[4], gpu::Usage::HostRead)});
        device_.submitAndWait(commands);
        std::vector<uint32_t> words(requestBytes_ / 4);
        std::memcpy(words.data(), device_.mappedPointer(buffers[4]), requestBytes_);
        release();
        return words;
    } catch (...) {
        release();
        throw;
    }
}

}  // namespace penumbra
