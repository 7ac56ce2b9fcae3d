#include "render/compute_raster_pass.h"

#include <algorithm>
#include <cstddef>

#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/main_pass.h"
#include "render/pass_layouts.h"

namespace penumbra {

namespace {

constexpr uint32_t kFarDepthBits = 0x3f800000u;  // floatBitsToUint(1.0): nothing cast
constexpr uint64_t kChunkBytes = 8;                // a queued chunk: (large piece, chunk x | y << 16)

}  // namespace

gpu::PipelineHandle createRasterArgsPipeline(gpu::Device& device, const char* debugName) {
    gpu::ComputePipelineDesc args;
    args.shader = "shadow_raster_args.comp";
    args.bindings = rasterArgsBindings();
    args.pushConstantSize = sizeof(gpu_data::RasterArgsConstants);
    args.debugName = debugName;
    return device.createComputePipeline(args);
}

void recordRasterDispatchSize(gpu::CommandList& commands, std::string_view passName, gpu::PipelineHandle args,
                              gpu::BufferHandle counters, const gpu_data::RasterArgsConstants& constants) {
    commands.pass(passName, {gpu::use(counters, gpu::Usage::ComputeWrite)});
    commands.bindPipeline(args);
    const gpu::DescriptorWrite write{gpu_data::kRasterBindingCounters, counters, {}, {}};
    commands.pushDescriptors(std::span(&write, 1));
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatch(1, 1);
}

void rasterReads(const GpuScene& scene, const ShadowCullingPass& culling, std::vector<gpu::ResourceUse>& uses) {
    using gpu::Usage;
    uses.assign({gpu::use(scene.cullMeshBuffer(), Usage::ComputeRead), gpu::use(scene.indexBuffer(), Usage::ComputeRead),
                 gpu::use(scene.meshletBuffer(), Usage::ComputeRead), gpu::use(culling.listCounts(), Usage::ComputeRead)});
    culling.addVisibleListUses(uses, Usage::ComputeRead);
    scene.addSceneReads(uses, Usage::ComputeRead);
}

void appendRasterMeshWrites(std::vector<gpu::DescriptorWrite>& writes, const GpuScene& gpuScene,
                            const ShadowCullingPass& culling, const RasterQueues& queues) {
    using namespace gpu_data;
    writes.push_back({kRasterBindingMeshes, gpuScene.cullMeshBuffer(), {}, {}});
    writes.push_back({kRasterBindingIndices, gpuScene.indexBuffer(), {}, {}});
    writes.push_back({kRasterBindingCounters, queues.counters, {}, {}});
    writes.push_back({kRasterBindingLargePieces, queues.large, {}, {}});
    writes.push_back({kRasterBindingChunks, queues.chunks, {}, {}});
    writes.push_back({kRasterBindingListCounts, culling.listCounts(), {}, {}});
    culling.appendVisibleListWrites(writes, kRasterBindingVisibleInstances);
    writes.push_back({kRasterBindingMeshlets, gpuScene.meshletBuffer(), {}, {}});
}

ComputeRasterPass::ComputeRasterPass(gpu::Device& device, const GpuScene& gpuScene, uint32_t largeQueue,
                                     uint32_t chunkQueue, uint32_t workQueue)
    : device_(device), scene_(gpuScene) {
    try {
        create(largeQueue, chunkQueue, workQueue);
    } catch (...) {
        destroyAll();  // a failed allocation half-way: the destructor does not run
        throw;
    }
}

void ComputeRasterPass::create(uint32_t largeQueue, uint32_t chunkQueue, uint32_t workQueue) {
    gpu::Device& device = device_;
    const GpuScene& gpuScene = scene_;
    gpu::ComputePipelineDesc desc;
    desc.bindings = shadowRasterBindings();
    desc.pushConstantSize = sizeof(gpu_data::ShadowRasterConstants);
    desc.textureTable = gpuScene.textureTable();
    for (auto [pipeline, shader] : {std::pair{&clear_, "shadow_raster_clear.comp"}, std::pair{&expand_, "shadow_raster_expand.comp"},
                                    std::pair{&small_, "shadow_raster.comp"}, std::pair{&bin_, "shadow_raster_bin.comp"},
                                    std::pair{&chunks_, "shadow_raster_chunks.comp"}}) {
        desc.shader = shader;
        desc.debugName = shader;
        *pipeline = device.createComputePipeline(desc);
    }
    args_ = createRasterArgsPipeline(device, "shadow raster dispatch sizes");
    using gpu::MemoryKind;
    counters_ = device.createBuffer(sizeof(gpu_data::RasterCounters), gpu::kBufferStorage | gpu::kBufferIndirect,
                                    MemoryKind::DeviceLocal, nullptr, "shadow raster counters");
    // Exactly the asked sizes (tests ask for small queues to see them overflow); later growth doubles.
    const uint32_t large = largeQueue ? largeQueue : gpu_data::kRasterInitialLarge;
    const uint32_t chunks = chunkQueue ? chunkQueue : gpu_data::kRasterInitialChunks;
    const uint32_t work = workQueue ? workQueue : gpu_data::kRasterInitialWork;
    resizeQueues(std::min(large, maxLargeCapacity()), std::min(chunks, maxChunkCapacity()), std::min(work, kMaxWorkCapacity));
}

uint32_t ComputeRasterPass::queueCapacityFor(uint32_t capacity, uint32_t needed, uint32_t limit) {
    if (2 * uint64_t(needed) <= capacity) return std::min(capacity, limit);
    return uint32_t(std::min<uint64_t>(std::max(2 * uint64_t(capacity), 2 * uint64_t(needed)), limit));
}

uint32_t ComputeRasterPass::maxLargeCapacity() const {
    return uint32_t(std::min<uint64_t>(kMaxLargeCapacity, device_.maxStorageBufferRange() / sizeof(gpu_data::RasterPiece)));
}

uint32_t ComputeRasterPass::maxChunkCapacity() const {
    return uint32_t(std::min<uint64_t>(kMaxChunkCapacity, device_.maxStorageBufferRange() / kChunkBytes));
}

void ComputeRasterPass::reserve(uint32_t largePieces, uint32_t chunks, uint32_t workItems) {
    // Queues of at least twice the most a frame asked for (capped: 4M pieces = 448 MB), each within the device's
    // largest storage buffer (a pass binds each whole; 1.2M pieces of 128 MiB): a frame that needs more
    // gets the warning that the queues were full, as one past the caps always did. Work items of 16
    // bytes: the 8M cap is 128 MiB, the storage buffer range every Vulkan device offers.
    resizeQueues(queueCapacityFor(largeCapacity_, largePieces, maxLargeCapacity()),
                 queueCapacityFor(chunkCapacity_, chunks, maxChunkCapacity()),
                 queueCapacityFor(workCapacity_, workItems, kMaxWorkCapacity));
}

void ComputeRasterPass::resizeQueues(uint32_t large, uint32_t chunkCount, uint32_t workCount) {
    if (workCount != workCapacity_ || !work_) {
        device_.destroy(work_);
        work_ = device_.createBuffer(uint64_t(workCount) * sizeof(gpu_data::RasterWorkItem), gpu::kBufferStorage,
                                     gpu::MemoryKind::DeviceLocal, nullptr, "shadow raster work items");
        workCapacity_ = workCount;
    }
    if (large_ && large == largeCapacity_ && chunkCount == chunkCapacity_) return;
    device_.destroy(large_);
    device_.destroy(chunkList_);
    large_ = device_.createBuffer(uint64_t(large) * sizeof(gpu_data::RasterPiece), gpu::kBufferStorage,
                                  gpu::MemoryKind::DeviceLocal, nullptr, "shadow raster large pieces");
    chunkList_ = device_.createBuffer(uint64_t(chunkCount) * kChunkBytes, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal,
                                      nullptr, "shadow raster chunks");
    largeCapacity_ = large;
    chunkCapacity_ = chunkCount;
}

ComputeRasterPass::~ComputeRasterPass() { destroyAll(); }

void ComputeRasterPass::destroyAll() {
    for (gpu::PipelineHandle p : {clear_, expand_, small_, bin_, chunks_, args_}) device_.destroy(p);
    for (gpu::BufferHandle b : {counters_, large_, chunkList_, work_}) device_.destroy(b);
}

void ComputeRasterPass::prepare(const std::vector<gpu::DescriptorWrite>& writes, const RasterTileLists& lists,
                                const ShadowCullingPass& culling, gpu::BufferHandle depth, uint32_t depthSide,
                                const ShadowRasterOptions& options) {
    using namespace gpu_data;
    lists_ = lists;
    writes_.assign(writes.begin(), writes.end());
    writes_.push_back({kShadowRasterBindingCullFrame, lists.cullFrame});
    writes_.push_back({kShadowRasterBindingAtlasDepth, gpu::BufferSlice{depth, 0, uint64_t(depthSide) * depthSide * 4}});
    writes_.push_back({kShadowRasterBindingTiles, lists.tiles});
    writes_.push_back({kShadowRasterBindingRasterList, lists.rasterList});
    writes_.push_back({kShadowRasterBindingWork, work_, {}, {}});
    appendRasterMeshWrites(writes_, scene_, culling, {counters_, large_, chunkList_});
    constants_ = {depthSide,     options.meshletCulling ? 1u : 0u, largeCapacity_,          chunkCapacity_,
                  workCapacity_, culling.listsPerBuffer(),        options.lodErrorTexels, 0};
    rasterReads(scene_, culling, reads_);
}

void ComputeRasterPass::bind(gpu::CommandList& commands, gpu::PipelineHandle pipeline) {
    commands.bindPipeline(pipeline);
    commands.pushDescriptors(writes_);
    commands.bindTextureTable(scene_.textureTable());
    commands.pushConstants(&constants_, sizeof(constants_));
}

// Pass 0: the listed tiles' viewports to far, one dispatch over the list (its clearDispatch).
void ComputeRasterPass::recordClearTiles(gpu::CommandList& commands, std::string_view timerPrefix, gpu::BufferHandle depth) {
    using gpu::Usage;
    const gpu::BufferSlice& list = lists_.rasterList;
    commands.pass(commands.joinName(timerPrefix, "/clear tiles"),
                  {gpu::use(depth, Usage::ComputeWrite), gpu::use(list.buffer, Usage::IndirectArguments),
                   gpu::use(list.buffer, Usage::ComputeRead), gpu::use(lists_.tiles.buffer, Usage::ComputeRead)});
    bind(commands, clear_);
    commands.dispatchIndirect(list.buffer, list.offset + offsetof(gpu_data::RasterTileListHeader, clearDispatch));
}

// Passes 1-3: per (work item, listed tile), then the queued large pieces and their chunks.
void ComputeRasterPass::recordDraw(gpu::CommandList& commands, std::string_view timerPrefix, gpu::BufferHandle depth) {
    using gpu::Usage;
    auto stepName = [&](std::string_view step) { return commands.joinName(timerPrefix, step); };
    auto pass = [&](const char* step, std::initializer_list<gpu::ResourceUse> more) {
        commands.pass(stepName(step), commands.joinUses(reads_, more));
    };
    auto sizeDispatch = [&](const char* step, uint32_t queue) {
        recordRasterDispatchSize(commands, stepName(step), args_, counters_, {queue, largeCapacity_, chunkCapacity_, workCapacity_});
    };
    const gpu::BufferSlice& list = lists_.rasterList;
    commands.beginTimer(stepName("/instances"));
    pass("/expand", {gpu::use(counters_, Usage::ComputeWrite), gpu::use(work_, Usage::ComputeWrite),
                     gpu::use(list.buffer, Usage::IndirectArguments), gpu::use(list.buffer, Usage::ComputeRead),
                     gpu::use(lists_.tiles.buffer, Usage::ComputeRead)});
    bind(commands, expand_);
    commands.dispatchIndirect(list.buffer, list.offset + offsetof(gpu_data::RasterTileListHeader, expandDispatch));
    sizeDispatch("/instances size", gpu_data::kRasterArgsWork);
    pass("/instances", {gpu::use(depth, Usage::ComputeWrite), gpu::use(counters_, Usage::ComputeWrite),
                        gpu::use(counters_, Usage::IndirectArguments), gpu::use(large_, Usage::ComputeWrite),
                        gpu::use(work_, Usage::ComputeRead), gpu::use(lists_.tiles.buffer, Usage::ComputeRead)});
    bind(commands, small_);
    commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, workDispatch));
    commands.endTimer();
    commands.beginTimer(stepName("/chunks"));
    sizeDispatch("/bin size", gpu_data::kRasterArgsLarge);
    pass("/bin", {gpu::use(large_, Usage::ComputeRead), gpu::use(counters_, Usage::IndirectArguments),
                  gpu::use(counters_, Usage::ComputeWrite), gpu::use(chunkList_, Usage::ComputeWrite)});
    bind(commands, bin_);
    commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, largeDispatch));
    sizeDispatch("/chunks size", gpu_data::kRasterArgsChunks);
    pass("/chunks", {gpu::use(large_, Usage::ComputeRead), gpu::use(chunkList_, Usage::ComputeRead),
                     gpu::use(counters_, Usage::IndirectArguments), gpu::use(counters_, Usage::ComputeRead),
                     gpu::use(depth, Usage::ComputeWrite)});
    bind(commands, chunks_);
    commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, chunkDispatch));
    commands.endTimer();
}

void ComputeRasterPass::record(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes,
                               const RasterTileLists& lists, const ShadowCullingPass& culling, const AtlasTiles& tiles,
                               uint32_t atlasSize, gpu::BufferHandle depth, const ShadowRasterOptions& options,
                               std::string_view timerPrefix) {
    using gpu::Usage;
    // Step names: timerPrefix + step in the command list's scratch (a timer keeps its own copy).
    auto stepName = [&](std::string_view step) { return commands.joinName(timerPrefix, step); };
    if (tiles.rects.empty() && !tiles.freshAtlas) {  // every tile cached: the depth stays as it is
        commands.pass(stepName("/clear"), {gpu::use(counters_, Usage::TransferWrite)});
        commands.fillBuffer(counters_, 0);  // nothing queued (its counters are read back)
        return;
    }
    prepare(writes, lists, culling, depth, atlasSize, options);
    commands.beginTimer(stepName("/clear"));
    const gpu::ResourceUse clears[2] = {gpu::use(counters_, Usage::TransferWrite), gpu::use(depth, Usage::TransferWrite)};
    commands.pass(stepName("/clear"), std::span(clears, tiles.freshAtlas ? 2 : 1));
    if (tiles.freshAtlas) commands.fillBuffer(depth, kFarDepthBits);
    commands.fillBuffer(counters_, 0);
    // The CPU wrote the list: it knows when there is nothing to draw (a fresh atlas of cached tiles).
    if (!tiles.freshAtlas && !tiles.rects.empty()) recordClearTiles(commands, timerPrefix, depth);
    commands.endTimer();
    if (!tiles.rects.empty()) recordDraw(commands, timerPrefix, depth);
}

void ComputeRasterPass::recordTiles(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes,
                                    const RasterTileLists& lists, const ShadowCullingPass& culling, gpu::BufferHandle depth,
                                    uint32_t depthSide, const ShadowRasterOptions& options,
                                    std::string_view timerPrefix) {
    prepare(writes, lists, culling, depth, depthSide, options);
    const std::string_view clearName = commands.joinName(timerPrefix, "/clear");
    commands.beginTimer(clearName);
    commands.pass(clearName, {gpu::use(counters_, gpu::Usage::TransferWrite)});
    commands.fillBuffer(counters_, 0);
    recordClearTiles(commands, timerPrefix, depth);
    commands.endTimer();
    recordDraw(commands, timerPrefix, depth);
}

}  // namespace penumbra
