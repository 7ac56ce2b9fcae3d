#include "render/virtual_page_table_pass.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "core/error.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

namespace {

using gpu::Usage;

constexpr const char* kShaders[] = {"virtual_page_reset.comp",      "virtual_page_invalidate.comp",
                                    "virtual_page_update.comp",     "virtual_page_requests.comp",
                                    "virtual_page_plan.comp",       "virtual_page_candidates.comp",
                                    "virtual_page_allocate.comp",   "virtual_page_finish.comp",
                                    "virtual_page_order.comp",      "virtual_page_drawn.comp"};
constexpr uint32_t kMaxGroups = 65535;  // the guaranteed maxComputeWorkGroupCount[0]

uint32_t groupsFor(uint32_t invocations) {
    return (invocations + gpu_data::kVirtualPageGroupSize - 1) / gpu_data::kVirtualPageGroupSize;
}

template <typename T>
std::vector<T> copyOut(const std::vector<uint8_t>& bytes, size_t offset, size_t count) {
    std::vector<T> values(count);
    std::memcpy(values.data(), bytes.data() + offset, count * sizeof(T));
    return values;
}

}  // namespace

namespace {

gpu_data::VirtualPageTableData packTableShape(const VirtualPageTableLayout& layout, uint32_t frame, uint32_t capacity,
                                              uint32_t keepFrames) {
    gpu_data::VirtualPageTableData data{};
    data.frame = frame;
    data.levelCount = layout.levelCount;
    data.pagesPerSide = layout.pagesPerSide;
    data.keepFrames = keepFrames;
    data.capacity = capacity;
    data.entryCount = layout.entryCount();
    data.levelsPerBucket = layout.levelsPerBucket;
    data.fixedWindows = layout.fixedWindows ? 1u : 0u;
    data.drawBudget = capacity;
    return data;
}

}  // namespace

gpu_data::VirtualPageTableData packVirtualPageTable(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                                                    uint32_t frame, uint32_t capacity, uint32_t keepFrames) {
    PENUMBRA_ASSERT(config.levelCount <= gpu_data::kVirtualPageMaxLevels);
    gpu_data::VirtualPageTableData data = packTableShape(clipmapTableLayout(config), frame, capacity, keepFrames);
    packClipmapWindows(config, lsCamera, data.levels);
    return data;
}

gpu_data::VirtualPageInvalidation virtualPageInvalidation(uint32_t level, const PageRect& pages) {
    gpu_data::VirtualPageInvalidation rect{};
    rect.minPageX = pages.min.x;
    rect.minPageY = pages.min.y;
    rect.maxPageX = pages.max.x;
    rect.maxPageY = pages.max.y;
    rect.level = level;
    return rect;
}

VirtualPageTablePass::VirtualPageTablePass(gpu::Device& device, const VirtualClipmapConfig& config, uint32_t capacity,
                                           uint32_t keepFrames, const VirtualPageStorage* shared)
    : device_(device), config_(config), layout_(clipmapTableLayout(config)), capacity_(capacity), keepFrames_(keepFrames),
      drawBudget_(capacity) {
    create(shared);
}

VirtualPageTablePass::VirtualPageTablePass(gpu::Device& device, const VirtualPageTableLayout& layout, uint32_t capacity,
                                           uint32_t keepFrames)
    : device_(device), layout_(layout), capacity_(capacity), keepFrames_(keepFrames), drawBudget_(capacity) {
    if (!layout.fixedWindows || layout.levelsPerBucket == 0)
        throw Error("internal: a virtual page table of fixed windows needs fixedWindows and levelsPerBucket >= 1");
    create(nullptr);
}

void VirtualPageTablePass::create(const VirtualPageStorage* shared) {
    const uint32_t capacity = capacity_, keepFrames = keepFrames_;
    entryCount_ = layout_.entryCount();
    if (layout_.levelCount == 0 || layout_.bucketCount() > gpu_data::kVirtualPageMaxLevels ||
        (!layout_.fixedWindows && layout_.levelsPerBucket != 1))
        throw Error("virtual page table: " + std::to_string(layout_.levelCount) + " levels (1 to " +
                    std::to_string(gpu_data::kVirtualPageMaxLevels) + " buckets)");
    if (capacity == 0 || capacity > kMaxGroups)
        throw Error("virtual page table: a pool of " + std::to_string(capacity) + " pages (1 to 65535)");
    if (keepFrames > gpu_data::kVirtualPageMaxKeepFrames)
        throw Error("virtual page table: keepFrames " + std::to_string(keepFrames) + " (at most " +
                    std::to_string(gpu_data::kVirtualPageMaxKeepFrames) + ")");
    if (groupsFor(std::max(entryCount_, capacity)) > kMaxGroups)
        throw Error("virtual page table: " + std::to_string(entryCount_) + " page-table entries are too many");
    if (shared && shared->entries) useSharedEntries(*shared);
    try {
        for (uint32_t step = 0; step < StepCount; ++step) {
            gpu::ComputePipelineDesc desc;
            desc.shader = kShaders[step];
            desc.bindings = virtualPageTableBindings(desc.shader);
            desc.debugName = desc.shader;
            pipelines_[step] = device_.createComputePipeline(desc);
        }
        createBuffers();
    } catch (...) {
        release();  // the destructor does not run
        throw;
    }
}

VirtualPageTablePass::~VirtualPageTablePass() { release(); }

void VirtualPageTablePass::useSharedEntries(const VirtualPageStorage& shared) {
    const uint64_t offset = uint64_t(shared.firstEntry) * sizeof(gpu_data::VirtualPageEntry);
    if (offset % kVirtualPageEntryAlignment != 0)
        throw Error("internal: a shared virtual page table at entry " + std::to_string(shared.firstEntry) + " (byte " +
                    std::to_string(offset) + ", not a multiple of 256)");
    if (offset + entryBytes() > device_.bufferSize(shared.entries))
        throw Error("internal: a shared virtual page table of " + std::to_string(device_.bufferSize(shared.entries)) +
                    " bytes holds no " + std::to_string(entryCount_) + " entries from entry " + std::to_string(shared.firstEntry));
    entries_ = shared.entries;
    entriesOffset_ = offset;
    ownsEntries_ = false;
}

void VirtualPageTablePass::release() {
    if (ownsEntries_) device_.destroy(entries_);  // shared entries are their storage's
    for (gpu::BufferHandle b : {owners_, pool_, counters_, candidates_, drawList_, missing_, testRequests_, testTable_,
                                testInvalidations_})
        device_.destroy(b);
    for (gpu::PipelineHandle p : pipelines_) device_.destroy(p);
}

void VirtualPageTablePass::createBuffers() {
    const uint32_t storage = gpu::kBufferStorage | gpu::kBufferTransferSrc;  // TransferSrc: readState
    const auto create = [&](uint64_t bytes, uint32_t usage, const char* name) {
        return device_.createBuffer(bytes, usage, gpu::MemoryKind::DeviceLocal, nullptr, name);
    };
    if (ownsEntries_) entries_ = create(entryBytes(), storage, "virtual page table");
    owners_ = create(uint64_t(capacity_) * 4, storage, "virtual page owners");
    pool_ = create(sizeof(gpu_data::VirtualPagePoolHeader) + uint64_t(capacity_) * 4, storage, "virtual page free list");
    counters_ = create(sizeof(gpu_data::VirtualPageCounters), storage | gpu::kBufferTransferDst | gpu::kBufferIndirect,
                       "virtual page counters");
    missing_ = create(uint64_t(entryCount_) * 4, storage, "virtual page missing entries");
    candidates_ = create(uint64_t(capacity_) * 4, storage, "virtual page eviction order");
    // The list, then as many draws in the order the update appends them (VirtualPageDrawHeader).
    drawList_ = create(sizeof(gpu_data::VirtualPageDrawHeader) + 2 * uint64_t(capacity_) * sizeof(gpu_data::VirtualPageDraw),
                       storage | gpu::kBufferTransferDst | gpu::kBufferIndirect, "virtual page draw list");
}

gpu_data::VirtualPageTableData VirtualPageTablePass::packFrame(const glm::vec2& lsCamera, bool invalidateAll,
                                                               uint32_t invalidationCount) {
    gpu_data::VirtualPageTableData data = layout_.fixedWindows
                                              ? packTableShape(layout_, ++frame_, capacity_, keepFrames_)
                                              : packVirtualPageTable(config_, lsCamera, ++frame_, capacity_, keepFrames_);
    data.invalidateAll = invalidateAll ? 1u : 0u;
    data.invalidationCount = invalidationCount;
    data.drawBudget = drawBudget_;
    return data;
}

void VirtualPageTablePass::setDrawBudget(uint32_t pages) { drawBudget_ = std::clamp(pages, 1u, capacity_); }

void VirtualPageTablePass::bindStep(gpu::CommandList& commands, Step step) {
    commands.bindPipeline(pipelines_[step]);
    commands.pushDescriptors(writes_);  // each step's pipeline takes the bindings it declares
}

void VirtualPageTablePass::dispatch(gpu::CommandList& commands, Step step, uint32_t groups) {
    bindStep(commands, step);
    commands.dispatch(groups, 1);
}

void VirtualPageTablePass::record(gpu::CommandList& commands, const VirtualPageTableInputs& inputs) {
    PENUMBRA_ASSERT(inputs.invalidationCount <= kMaxGroups);
    writes_ = {gpu::DescriptorWrite{gpu_data::kPageTableBindingFrame, inputs.tableData},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingRequests, inputs.requestWords},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingEntries, entriesSlice()},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingOwners, owners_, {}, {}},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingPool, pool_, {}, {}},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingCounters, counters_, {}, {}},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingCandidates, candidates_, {}, {}},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingDrawList, drawList_, {}, {}},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingInvalidations, inputs.invalidations},
               gpu::DescriptorWrite{gpu_data::kPageTableBindingMissing, missing_, {}, {}}};
    if (needsReset_) {  // the bound range only: a shared buffer's other tables keep their entries
        commands.pass("virtualPageTable/reset", {gpu::use(entries_, Usage::ComputeWrite),
                                                 gpu::use(owners_, Usage::ComputeWrite), gpu::use(pool_, Usage::ComputeWrite)});
        dispatch(commands, Reset, groupsFor(std::max(entryCount_, capacity_)));
        needsReset_ = false;
    }
    commands.pass("virtualPageTable/clear",
                  {gpu::use(counters_, Usage::TransferWrite), gpu::use(drawList_, Usage::TransferWrite)});
    commands.fillBuffer(counters_, 0u);
    commands.fillBuffer({drawList_, 0, sizeof(gpu_data::VirtualPageDrawHeader)}, 0u);
    if (inputs.invalidationCount > 0) {
        commands.pass("virtualPageTable/invalidate", {gpu::use(entries_, Usage::ComputeWrite)});
        dispatch(commands, Invalidate, inputs.invalidationCount);  // one workgroup per rectangle
    }
    commands.pass("virtualPageTable/update",
                  {gpu::use(inputs.requestWords.buffer, Usage::ComputeRead), gpu::use(entries_, Usage::ComputeWrite),
                   gpu::use(owners_, Usage::ComputeWrite), gpu::use(pool_, Usage::ComputeWrite),
                   gpu::use(counters_, Usage::ComputeWrite), gpu::use(drawList_, Usage::ComputeWrite)});
    dispatch(commands, Update, groupsFor(capacity_));  // one invocation per physical page
    commands.pass("virtualPageTable/requests",
                  {gpu::use(inputs.requestWords.buffer, Usage::ComputeRead), gpu::use(entries_, Usage::ComputeWrite),
                   gpu::use(counters_, Usage::ComputeWrite), gpu::use(missing_, Usage::ComputeWrite)});
    dispatch(commands, Requests, groupsFor((entryCount_ + 31) / 32));  // one invocation per word of request bits
    commands.pass("virtualPageTable/plan", {gpu::use(pool_, Usage::ComputeRead), gpu::use(counters_, Usage::ComputeWrite)});
    dispatch(commands, Plan, 1);
    commands.pass("virtualPageTable/candidates",
                  {gpu::use(inputs.requestWords.buffer, Usage::ComputeRead), gpu::use(entries_, Usage::ComputeRead),
                   gpu::use(owners_, Usage::ComputeRead), gpu::use(counters_, Usage::ComputeWrite),
                   gpu::use(candidates_, Usage::ComputeWrite)});
    dispatch(commands, Candidates, groupsFor(capacity_));
    commands.pass("virtualPageTable/allocate",
                  {gpu::use(entries_, Usage::ComputeWrite), gpu::use(owners_, Usage::ComputeWrite),
                   gpu::use(pool_, Usage::ComputeRead), gpu::use(counters_, Usage::ComputeWrite),
                   gpu::use(counters_, Usage::IndirectArguments), gpu::use(candidates_, Usage::ComputeRead),
                   gpu::use(drawList_, Usage::ComputeWrite), gpu::use(missing_, Usage::ComputeRead)});
    bindStep(commands, Allocate);  // over the missing entries: the plan sized the dispatch
    commands.dispatchIndirect(counters_, offsetof(gpu_data::VirtualPageCounters, allocateDispatch));
    commands.pass("virtualPageTable/finish", {gpu::use(pool_, Usage::ComputeWrite), gpu::use(counters_, Usage::ComputeWrite),
                                              gpu::use(drawList_, Usage::ComputeWrite)});
    dispatch(commands, Finish, 1);
    commands.pass("virtualPageTable/order", {gpu::use(counters_, Usage::ComputeWrite), gpu::use(drawList_, Usage::IndirectArguments),
                                             gpu::use(drawList_, Usage::ComputeWrite)});
    bindStep(commands, Order);  // over the appended pages: the finish sized the dispatch
    commands.dispatchIndirect(drawList_, offsetof(gpu_data::VirtualPageDrawHeader, listDispatch));
}

void VirtualPageTablePass::recordMarkDrawn(gpu::CommandList& commands) {
    commands.pass("virtualPageTable/drawn", {gpu::use(drawList_, Usage::IndirectArguments), gpu::use(drawList_, Usage::ComputeRead),
                                             gpu::use(entries_, Usage::ComputeWrite)});
    commands.bindPipeline(pipelines_[Drawn]);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kPageTableBindingEntries, entriesSlice()},
                                           {gpu_data::kPageTableBindingDrawList, drawList_, {}, {}}};
    commands.pushDescriptors(writes);
    commands.dispatchIndirect(drawList_, offsetof(gpu_data::VirtualPageDrawHeader, listDispatch));
}

gpu::BufferSlice VirtualPageTablePass::levelStats() const {
    return {counters_, offsetof(gpu_data::VirtualPageCounters, levelRequested), sizeof(gpu_data::VirtualPageLevelStats)};
}

gpu::BufferSlice VirtualPageTablePass::stats() const {
    return {counters_, offsetof(gpu_data::VirtualPageCounters, stats), sizeof(gpu_data::VirtualPageStats)};
}

void VirtualPageTablePass::ensureTestBuffers(size_t requestBytes, size_t invalidationCount) {
    const auto hostBuffer = [&](size_t bytes, uint32_t usage, const char* name) {
        return device_.createBuffer(bytes, usage, gpu::MemoryKind::HostVisible, nullptr, name);
    };
    if (!testTable_)
        testTable_ = hostBuffer(sizeof(gpu_data::VirtualPageTableData), gpu::kBufferUniform, "virtual page table data");
    if (requestBytes != testRequestBytes_) {
        device_.destroy(testRequests_);
        testRequests_ = hostBuffer(requestBytes, gpu::kBufferStorage, "virtual page test requests");
        testRequestBytes_ = requestBytes;
    }
    if (invalidationCount > testInvalidationCapacity_ || !testInvalidations_) {
        device_.destroy(testInvalidations_);
        testInvalidationCapacity_ = std::max<size_t>(invalidationCount, 1);
        testInvalidations_ = hostBuffer(testInvalidationCapacity_ * sizeof(gpu_data::VirtualPageInvalidation),
                                        gpu::kBufferStorage, "virtual page test invalidations");
    }
}

void VirtualPageTablePass::updateNow(std::span<const uint32_t> requestWords, const glm::vec2& lsCamera, bool invalidateAll,
                                     std::span<const gpu_data::VirtualPageInvalidation> invalidations) {
    ensureTestBuffers(requestWords.size_bytes(), invalidations.size());
    const gpu_data::VirtualPageTableData data = packFrame(lsCamera, invalidateAll, uint32_t(invalidations.size()));
    // Each call waits for its submission: nothing on the GPU reads these buffers while they are written.
    device_.writeBuffer(testTable_, &data, sizeof(data));
    device_.writeBuffer(testRequests_, requestWords.data(), requestWords.size_bytes());
    if (!invalidations.empty()) device_.writeBuffer(testInvalidations_, invalidations.data(), invalidations.size_bytes());
    gpu::CommandList commands = device_.beginCommands();
    record(commands, {{testRequests_, 0, requestWords.size_bytes()},
                      {testTable_, 0, sizeof(data)},
                      {testInvalidations_, 0, testInvalidationCapacity_ * sizeof(gpu_data::VirtualPageInvalidation)},
                      uint32_t(invalidations.size())});
    device_.submitAndWait(commands);
}

void VirtualPageTablePass::markDrawnNow() {
    gpu::CommandList commands = device_.beginCommands();
    recordMarkDrawn(commands);
    device_.submitAndWait(commands);
}

VirtualPageTableState VirtualPageTablePass::readState() {
    using namespace gpu_data;
    VirtualPageTableState state;
    state.entries = copyOut<VirtualPageEntry>(device_.readBuffer(entries_), entriesOffset_, entryCount_);
    state.owners = copyOut<uint32_t>(device_.readBuffer(owners_), 0, capacity_);
    const std::vector<uint8_t> pool = device_.readBuffer(pool_);
    const VirtualPagePoolHeader header = copyOut<VirtualPagePoolHeader>(pool, 0, 1)[0];
    state.freePages = copyOut<uint32_t>(pool, sizeof(header), std::min(header.freeCount, capacity_));
    state.stats = copyOut<VirtualPageCounters>(device_.readBuffer(counters_), 0, 1)[0].stats;
    const std::vector<uint8_t> drawList = device_.readBuffer(drawList_);
    state.drawHeader = copyOut<VirtualPageDrawHeader>(drawList, 0, 1)[0];
    state.draws = copyOut<VirtualPageDraw>(drawList, sizeof(VirtualPageDrawHeader), std::min(state.drawHeader.count, capacity_));
    return state;
}

}  // namespace penumbra
