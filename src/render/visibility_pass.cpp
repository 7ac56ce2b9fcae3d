#include "render/visibility_pass.h"

#include <algorithm>
#include <cmath>

#include "cull_structs.h"
#include "render/compute_raster_pass.h"
#include "pass_bindings.h"
#include "render/main_pass.h"
#include "render/pass_layouts.h"
#include "shadows/cull_packing.h"
#include "visibility_structs.h"

namespace penumbra {

namespace {

uint32_t packRgba8(const float color[4], bool srgb) {
    uint32_t packed = 0;
    for (int i = 0; i < 4; ++i) {
        float c = std::clamp(color[i], 0.0f, 1.0f);
        if (srgb && i < 3) c = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
        packed |= uint32_t(std::lround(c * 255.0f)) << (8 * i);
    }
    return packed;
}

}  // namespace

VisibilityPass::VisibilityPass(gpu::Device& device, const GpuScene& gpuScene)
    : device_(device), scene_(gpuScene), fragmentResolve_(device.info().isCpu && !device.faults().computeResolve) {
    try {
        create();
    } catch (...) {
        destroyAll();  // a failed allocation half-way: the destructor does not run
        throw;
    }
}

VisibilityPass::~VisibilityPass() { destroyAll(); }

bool VisibilityPass::supported(const gpu::Device& device, const GpuScene& gpuScene) {
    return device.hasBufferInt64Atomics() && gpuScene.visibilityIdsFit();
}

void VisibilityPass::create() {
    gpu::ComputePipelineDesc desc;
    desc.bindings = visibilityRasterBindings();
    desc.pushConstantSize = sizeof(gpu_data::VisibilityConstants);
    desc.textureTable = scene_.textureTable();
    for (auto [pipeline, shader] : {std::pair{&raster_, "visibility_raster.comp"}, std::pair{&rasterPacked_, "visibility_raster_packed.comp"},
                                    std::pair{&bin_, "visibility_raster_bin.comp"}, std::pair{&chunks_, "visibility_raster_chunks.comp"}}) {
        desc.shader = shader;
        desc.debugName = shader;
        *pipeline = device_.createComputePipeline(desc);
    }
    args_ = createRasterArgsPipeline(device_, "visibility raster dispatch sizes");
    gpu::ComputePipelineDesc pyramid;
    pyramid.shader = "depth_pyramid.comp";
    pyramid.bindings = depthPyramidBindings();
    pyramid.pushConstantSize = sizeof(gpu_data::PyramidConstants);
    pyramid.debugName = "main view depth pyramid";
    pyramid_ = device_.createComputePipeline(pyramid);
    using gpu::MemoryKind;
    counters_ = device_.createBuffer(sizeof(gpu_data::RasterCounters), gpu::kBufferStorage | gpu::kBufferIndirect,
                                     MemoryKind::DeviceLocal, nullptr, "visibility raster counters");
    large_ = device_.createBuffer(uint64_t(kLargeCapacity) * sizeof(gpu_data::RasterPiece), gpu::kBufferStorage,
                                  MemoryKind::DeviceLocal, nullptr, "visibility raster large pieces");
    chunkList_ = device_.createBuffer(uint64_t(kChunkCapacity) * 8, gpu::kBufferStorage, MemoryKind::DeviceLocal, nullptr,
                                      "visibility raster chunks");
}

void VisibilityPass::destroyAll() {
    for (gpu::PipelineHandle p : {raster_, rasterPacked_, bin_, chunks_, args_, pyramid_}) device_.destroy(p);
    for (ResolvePipeline& resolve : resolve_) device_.destroy(resolve.pipeline);
    resolve_.clear();
    for (gpu::BufferHandle b : {counters_, large_, chunkList_, visibility_, depth_, pyramidTexels_}) device_.destroy(b);
    device_.destroy(color_);
}

void VisibilityPass::ensureSize(uint32_t width, uint32_t height) {
    if (visibility_ && width == width_ && height == height_) return;
    for (gpu::BufferHandle b : {visibility_, depth_, pyramidTexels_}) device_.destroy(b);
    device_.destroy(color_);
    color_ = {};
    const uint64_t pixels = uint64_t(width) * height;
    using gpu::MemoryKind;
    pyramidLayout_ = depthPyramidLayout(width, height);
    pyramidTexels_ = device_.createBuffer(uint64_t(pyramidLayout_.texels) * 4, gpu::kBufferStorage,
                                          MemoryKind::DeviceLocal, nullptr, "main view depth pyramid");
    visibility_ = device_.createBuffer(pixels * 8, gpu::kBufferStorage | gpu::kBufferTransferDst, MemoryKind::DeviceLocal,
                                       nullptr, "visibility buffer");
    if (!fragmentResolve_)
        color_ = device_.createTexture({width, height, gpu::Format::RGBA8Unorm, gpu::kTextureStorage | gpu::kTextureTransferSrc, 1,
                                        "visibility resolved colour"});
    if (!fragmentResolve_) depth_ = device_.createBuffer(pixels * 4, gpu::kBufferStorage | gpu::kBufferTransferSrc, MemoryKind::DeviceLocal,
                                  nullptr, "visibility resolved depth");
    width_ = width;
    height_ = height;
}

gpu::PipelineHandle VisibilityPass::resolvePipeline(const std::vector<gpu::SpecConstant>& specialization,
                                                    gpu::Format colorFormat) {
    // The compute resolve writes buffers (one pipeline for every format); the fragment one the target.
    const gpu::Format format = fragmentResolve_ ? colorFormat : gpu::Format::Undefined;
    const auto sameConstant = [](const gpu::SpecConstant& a, const gpu::SpecConstant& b) {
        return a.id == b.id && a.value == b.value;
    };
    for (const ResolvePipeline& resolve : resolve_)
        if (resolve.format == format && std::equal(resolve.specialization.begin(), resolve.specialization.end(),
                                                   specialization.begin(), specialization.end(), sameConstant))
            return resolve.pipeline;
    resolve_.push_back({specialization, format, {}});
    gpu::PipelineHandle& pipeline = resolve_.back().pipeline;
    const std::vector<gpu::BindingDesc> bindings =
        visibilityResolveBindings(fragmentResolve_ ? gpu::kStageFragment : gpu::kStageCompute);
    if (fragmentResolve_) {
        gpu::GraphicsPipelineDesc desc;
        desc.vertexShader = "fullscreen.vert";
        desc.fragmentShader = "visibility_resolve.frag";
        desc.bindings = bindings;
        desc.pushConstantSize = sizeof(gpu_data::VisibilityConstants);
        desc.textureTable = scene_.textureTable();
        desc.colorFormats = {colorFormat};
        desc.depthFormat = gpu::Format::D32Float;
        desc.depthCompare = gpu::CompareOp::Always;
        desc.cullMode = gpu::CullMode::None;
        desc.specialization = specialization;
        desc.debugName = "visibility resolve (fragment)";
        pipeline = device_.createGraphicsPipeline(desc);
        return pipeline;
    }
    gpu::ComputePipelineDesc desc;
    desc.shader = "visibility_resolve.comp";
    desc.bindings = bindings;
    desc.pushConstantSize = sizeof(gpu_data::VisibilityConstants);
    desc.textureTable = scene_.textureTable();
    desc.specialization = specialization;
    desc.debugName = "visibility resolve";
    pipeline = device_.createComputePipeline(desc);
    return pipeline;
}

void VisibilityPass::recordResolve(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                                   const gpu_data::VisibilityConstants& constants) {
    using gpu::Usage;
    std::vector<gpu::DescriptorWrite>& resolveWrites = resolveWrites_;
    resolveWrites.assign(inputs.writes.begin(), inputs.writes.end());
    resolveWrites.push_back({gpu_data::kResolveBindingVisibility, visibility_, {}, {}});
    resolveWrites.push_back({gpu_data::kResolveBindingIndices, scene_.indexBuffer(), {}, {}});
    resolveWrites.push_back({gpu_data::kResolveBindingMeshes, scene_.cullMeshBuffer(), {}, {}});
    resolveWrites.push_back({gpu_data::kResolveBindingInstances, scene_.cullInstanceBuffer(), {}, {}});
    auto bind = [&]() {
        commands.bindPipeline(resolvePipeline(target.specialization, target.colorFormat));
        commands.pushDescriptors(resolveWrites);
        commands.bindTextureTable(scene_.textureTable());
        commands.pushConstants(&constants, sizeof(constants));
    };
    const Usage read = fragmentResolve_ ? Usage::GraphicsRead : Usage::ComputeRead;
    std::vector<gpu::ResourceUse>& uses = resolveUses_;
    uses = {gpu::use(visibility_, read), gpu::use(scene_.indexBuffer(), read), gpu::use(scene_.cullMeshBuffer(), read),
            gpu::use(scene_.cullInstanceBuffer(), read)};
    addShadingReads(uses, scene_, inputs, !fragmentResolve_);
    if (fragmentResolve_) {  // every pixel is written
        uses.push_back(gpu::discard(target.color, Usage::ColorTarget));
        uses.push_back(gpu::discard(target.depth, Usage::DepthTarget));
        commands.pass("main/resolve", uses);
        gpu::RenderingDesc rendering;
        rendering.width = target.width;
        rendering.height = target.height;
        gpu::ColorAttachment color;
        color.texture = target.color;
        color.clear = false;  // every pixel is written
        rendering.colors = std::span(&color, 1);
        rendering.depth = {target.depth, false, 0.0f};
        commands.beginRendering(rendering);
        bind();
        commands.draw(3);
        commands.endRendering();
        return;
    }
    resolveWrites.push_back({gpu_data::kResolveBindingColor, {}, color_, {}});
    resolveWrites.push_back({gpu_data::kResolveBindingDepth, depth_, {}, {}});
    uses.push_back(gpu::use(color_, Usage::ComputeWrite));
    uses.push_back(gpu::use(depth_, Usage::ComputeWrite));
    commands.pass("main/resolve", uses);
    bind();
    const uint32_t group = gpu_data::kResolveGroupSize;
    commands.dispatch((target.width + group - 1) / group, (target.height + group - 1) / group);
}

void VisibilityPass::recordRaster(gpu::CommandList& commands, std::string_view name,
                                  const std::vector<gpu::DescriptorWrite>& writes, const std::vector<gpu::ResourceUse>& reads,
                                  gpu_data::VisibilityConstants constants, uint32_t list, bool meshletCulling) {
    using gpu::Usage;
    constants.list = list;
    constants.instanceCount = scene_.instanceCount();
    constants.meshletCulling = meshletCulling ? 1u : 0u;
    auto bind = [&](gpu::PipelineHandle pipeline) {
        commands.bindPipeline(pipeline);
        commands.pushDescriptors(writes);
        commands.bindTextureTable(scene_.textureTable());
        commands.pushConstants(&constants, sizeof(constants));
    };
    // Pass names and uses joined in the command list's scratch (no allocation once warm).
    auto pass = [&](std::string_view step, std::initializer_list<gpu::ResourceUse> more) {
        commands.pass(commands.joinName(name, step), commands.joinUses(reads, more));
    };
    auto sizeDispatch = [&](const char* step, uint32_t queue) {
        recordRasterDispatchSize(commands, commands.joinName(name, step), args_, counters_,
                                 {queue, kLargeCapacity, kChunkCapacity, 0});
    };
    // The queues' counters; the meshlet counts add up over both phases of the frame.
    commands.pass(commands.joinName(name, "/clear"), {gpu::use(counters_, Usage::TransferWrite)});
    commands.fillBuffer(gpu::BufferSlice{counters_, 0, offsetof(gpu_data::RasterCounters, meshletsOutside)}, 0);
    const uint32_t items = std::max(scene_.rasterWorkItems(), 1u);
    pass("", {gpu::use(visibility_, Usage::ComputeWrite), gpu::use(counters_, Usage::ComputeWrite),
                gpu::use(large_, Usage::ComputeWrite)});
    // Two pipelines over the same items: meshlet items, then (if the scene has any) packed ones.
    for (const bool packed : {false, true}) {
        if (packed && !scene_.hasPackedMeshes()) continue;
        bind(packed ? rasterPacked_ : raster_);
        commands.dispatch(std::min(items, gpu_data::kRasterDispatchWidth),
                          (items + gpu_data::kRasterDispatchWidth - 1) / gpu_data::kRasterDispatchWidth);
    }
    sizeDispatch("/bin size", gpu_data::kRasterArgsLarge);
    pass("/bin", {gpu::use(large_, Usage::ComputeRead), gpu::use(counters_, Usage::IndirectArguments),
                         gpu::use(counters_, Usage::ComputeWrite), gpu::use(chunkList_, Usage::ComputeWrite)});
    bind(bin_);
    commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, largeDispatch));
    sizeDispatch("/chunks size", gpu_data::kRasterArgsChunks);
    pass("/chunks", {gpu::use(large_, Usage::ComputeRead), gpu::use(chunkList_, Usage::ComputeRead),
                            gpu::use(counters_, Usage::IndirectArguments), gpu::use(counters_, Usage::ComputeRead),
                            gpu::use(visibility_, Usage::ComputeWrite)});
    bind(chunks_);
    commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, chunkDispatch));
}

void VisibilityPass::recordPyramid(gpu::CommandList& commands) {
    const DepthPyramidLayout& layout = pyramidLayout_;
    commands.bindPipeline(pyramid_);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kPyramidBindingVisibility, visibility_, {}, {}},
                                                      {gpu_data::kPyramidBindingTexels, pyramidTexels_, {}, {}}};
    commands.pushDescriptors(writes);
    for (size_t level = 0; level < layout.sizes.size(); ++level) {
        const glm::uvec2 target = layout.sizes[level];
        gpu_data::PyramidConstants constants{};
        if (level == 0) {
            constants.sourceWidth = width_;
            constants.sourceHeight = height_;
            constants.fromVisibility = 1u;
        } else {
            constants.sourceOffset = layout.offsets[level - 1];
            constants.sourceWidth = layout.sizes[level - 1].x;
            constants.sourceHeight = layout.sizes[level - 1].y;
        }
        constants.targetOffset = layout.offsets[level];
        constants.targetWidth = target.x;
        constants.targetHeight = target.y;
        commands.pushConstants(&constants, sizeof(constants));
        const uint32_t group = gpu_data::kPyramidGroupSize;
        // Each level reads the one before (or the visibility buffer).
        commands.pass("main/pyramid", {gpu::use(visibility_, gpu::Usage::ComputeRead),
                                       gpu::use(pyramidTexels_, gpu::Usage::ComputeWrite)});
        commands.dispatch((target.x + group - 1) / group, (target.y + group - 1) / group);
    }
}

gpu_data::VisibilityConstants VisibilityPass::constantsFor(const Target& target) const {
    gpu_data::VisibilityConstants constants{};
    constants.width = target.width;
    constants.height = target.height;
    constants.triangleBits = scene_.triangleIdBits();
    constants.encodeSrgb = target.colorFormat == gpu::Format::RGBA8Srgb ? 1u : 0u;
    constants.largeCapacity = kLargeCapacity;
    constants.chunkCapacity = kChunkCapacity;
    constants.background = packRgba8(target.clearColor, false);
    constants.backgroundGradient = target.backgroundGradient ? 1u : 0u;
    constants.meshSlots = scene_.meshSlotCount();
    return constants;
}

void VisibilityPass::record(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                            ShadowCullingPass& culling, const gpu::BufferSlice& cullFrame, ViewCulling viewCulling,
                            bool meshletCulling) {
    recordGeometry(commands, inputs, target, culling, cullFrame, viewCulling, meshletCulling);
    recordShading(commands, inputs, target);
}

void VisibilityPass::recordGeometry(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target,
                                    ShadowCullingPass& culling, const gpu::BufferSlice& cullFrame, ViewCulling viewCulling,
                                    bool meshletCulling) {
    ensureSize(target.width, target.height);
    gpu_data::VisibilityConstants constants = constantsFor(target);
    constants.listsPerBuffer = culling.listsPerBuffer();
    using namespace gpu_data;
    std::vector<gpu::DescriptorWrite>& rasterWrites = rasterWrites_;  // the scene's (not the lit pass's: 8 is the visibility buffer here)
    rasterWrites.clear();
    for (const gpu::DescriptorWrite& w : inputs.writes)
        for (uint32_t scene : {kSceneBindingFrame, kSceneBindingVertices, kSceneBindingInstances, kSceneBindingMaterials})
            if (w.binding == scene) rasterWrites.push_back(w);
    rasterWrites.push_back({kVisibilityRasterBindingVisibility, visibility_, {}, {}});
    appendRasterMeshWrites(rasterWrites, scene_, culling, {counters_, large_, chunkList_});

    std::vector<gpu::ResourceUse>& reads = reads_;
    rasterReads(scene_, culling, reads);
    commands.beginTimer("main/cull");
    commands.pass("main/clear", {gpu::use(visibility_, gpu::Usage::TransferWrite), gpu::use(counters_, gpu::Usage::TransferWrite)});
    commands.fillBuffer(visibility_, 0);
    commands.fillBuffer(gpu::BufferSlice{counters_, offsetof(gpu_data::RasterCounters, meshletsOutside), 4 * sizeof(uint32_t)}, 0);
    culling.recordView(commands, cullFrame, gpu_data::kCullPassCameraEarly, pyramidTexels_);
    commands.endTimer();
    commands.beginTimer("main/raster");
    recordRaster(commands, "main/raster", rasterWrites, reads, constants, gpu_data::kCullListCameraEarly, meshletCulling);
    commands.endTimer();
    if (viewCulling == ViewCulling::Occlusion) {
        commands.beginTimer("main/occlusion");
        recordPyramid(commands);
        culling.recordView(commands, cullFrame, gpu_data::kCullPassCameraLate, pyramidTexels_);
        commands.endTimer();
        commands.beginTimer("main/rasterLate");
        recordRaster(commands, "main/rasterLate", rasterWrites, reads, constants, gpu_data::kCullListCameraLate, meshletCulling);
        commands.endTimer();
    }
}

void VisibilityPass::recordShading(gpu::CommandList& commands, const MainPassInputs& inputs, const Target& target) {
    const gpu_data::VisibilityConstants constants = constantsFor(target);
    commands.beginTimer("main/resolve");
    recordResolve(commands, inputs, target, constants);
    commands.endTimer();
    if (fragmentResolve_) return;
    commands.beginTimer("main/copy");
    using gpu::Usage;
    std::vector<gpu::ResourceUse>& uses = copyUses_;  // a member: its storage is reused frame to frame
    uses = {gpu::use(color_, Usage::TransferRead), gpu::discard(target.color, Usage::TransferWrite)};
    if (target.depthRead) uses.insert(uses.end(), {gpu::use(depth_, Usage::TransferRead), gpu::discard(target.depth, Usage::TransferWrite)});
    commands.pass("main/copy", uses);
    commands.copyTexture(color_, target.color);
    if (target.depthRead) commands.copyBufferToTexture(depth_, target.depth);
    commands.endTimer();
}

}  // namespace penumbra
