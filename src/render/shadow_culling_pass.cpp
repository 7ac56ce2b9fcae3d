#include "render/shadow_culling_pass.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "core/error.h"
#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

namespace {

static_assert(gpu_data::kCullListCameraEarly == gpu_data::kMaxCullTiles &&
              gpu_data::kCullListCameraLate + 1 == gpu_data::kCullListCount);
constexpr uint32_t kDrawCommandBytes = 5 * sizeof(uint32_t);  // VkDrawIndexedIndirectCommand

uint32_t groupsFor(uint32_t count) { return (count + gpu_data::kCullWorkgroupSize - 1) / gpu_data::kCullWorkgroupSize; }

}  // namespace

ShadowCullingPass::ShadowCullingPass(gpu::Device& device, const GpuScene& gpuScene, uint32_t tileCapacity)
    : device_(device), scene_(gpuScene), tileCapacity_(std::max(tileCapacity, 1u)),
      listCount_(std::max(tileCapacity_, gpu_data::kMaxCullTiles) + kViewLists) {
    try {
        create();
    } catch (...) {
        destroyAll();  // a failed allocation half-way: the destructor does not run
        throw;
    }
}

void ShadowCullingPass::create() {
    gpu::Device& device = device_;
    const GpuScene& gpuScene = scene_;
    gpu::ComputePipelineDesc desc;
    desc.shader = "shadow_cull.comp";
    desc.bindings = shadowCullBindings();
    desc.pushConstantSize = sizeof(gpu_data::CullConstants);
    desc.debugName = "shadow caster and main view culling";
    cull_ = device.createComputePipeline(desc);
    desc.shader = "shadow_draws.comp";
    desc.bindings = shadowDrawsBindings();
    desc.debugName = "shadow draw lists";
    buildDraws_ = device.createComputePipeline(desc);

    const uint64_t tiles = listCount_, meshes = gpuScene.meshSlotCount();
    const uint64_t instances = std::max(gpuScene.instanceCount(), 1u);
    using gpu::MemoryKind;
    listCounts_ = device.createBuffer(tiles * meshes * 4, gpu::kBufferStorage, MemoryKind::DeviceLocal, nullptr,
                                      "shadow cull list counts");
    const VisibleListSplit split =
        splitVisibleLists(instances, listCount_, device.maxStorageBufferRange(), visibleListBuffersOn(device));
    listsPerBuffer_ = split.listsPerBuffer;
    visibleBufferCount_ = split.bufferCount;
    for (uint32_t b = 0; b < visibleBufferCount_; ++b) {
        const uint64_t lists = std::min(listsPerBuffer_, listCount_ - b * listsPerBuffer_);
        const std::string name = "shadow visible instances" + (b > 0 ? " " + std::to_string(b) : std::string());
        visible_[b] = device.createBuffer(lists * instances * 4, gpu::kBufferStorage, MemoryKind::DeviceLocal, nullptr, name);
    }
    drawCommands_ = device.createBuffer(tiles * gpu_data::kCasterKinds * meshes * kDrawCommandBytes,
                                        gpu::kBufferStorage | gpu::kBufferIndirect, MemoryKind::DeviceLocal, nullptr,
                                        "shadow draw commands");
    drawCounts_ = device.createBuffer(tiles * gpu_data::kCasterKinds * 4, gpu::kBufferStorage | gpu::kBufferIndirect,
                                      MemoryKind::DeviceLocal, nullptr, "shadow draw counts");
    tileStats_ = device.createBuffer(tiles * sizeof(gpu_data::CullTileStats), gpu::kBufferStorage,
                                     MemoryKind::DeviceLocal, nullptr, "shadow tile stats");
    const std::vector<uint32_t> nothingVisible(instances, 0u);  // the first frame's late phase finds them all
    viewHistory_ = device.createBuffer(instances * 4, gpu::kBufferStorage, MemoryKind::DeviceLocal, nothingVisible.data(),
                                       "main view visibility history");
}

ShadowCullingPass::~ShadowCullingPass() { destroyAll(); }

void ShadowCullingPass::destroyAll() {
    device_.destroy(cull_);
    device_.destroy(buildDraws_);
    for (gpu::BufferHandle b : {listCounts_, drawCommands_, drawCounts_, tileStats_, viewHistory_}) device_.destroy(b);
    for (gpu::BufferHandle b : visible_) device_.destroy(b);
}

void ShadowCullingPass::record(gpu::CommandList& commands, const gpu::BufferSlice& cullFrame, const gpu::BufferSlice& tiles,
                               std::string_view passName) {
    using gpu::Usage;
    commands.pass(commands.joinName(passName, "/clear"), {gpu::use(listCounts_, Usage::TransferWrite), gpu::use(drawCounts_, Usage::TransferWrite),
                                            gpu::use(tileStats_, Usage::TransferWrite)});
    commands.clearBuffer(listCounts_, 0);
    commands.clearBuffer(drawCounts_, 0);
    commands.clearBuffer(tileStats_, 0);
    // The tile count is the list's (a GPU-written list's is known to the GPU only): both dispatches
    // are sized by its header.
    const gpu::ResourceUse tileArgs = gpu::use(tiles.buffer, Usage::IndirectArguments), tileReads = gpu::use(tiles.buffer, Usage::ComputeRead);
    commands.pass(passName, cullUses(viewHistory_, {tileArgs, tileReads}));
    commands.bindPipeline(cull_);
    commands.pushDescriptors(cullWrites(cullFrame, tiles, viewHistory_));  // no pyramid read: any buffer
    const gpu_data::CullConstants constants{gpu_data::kCullPassShadows, listsPerBuffer_, 0, 0};
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatchIndirect(tiles.buffer, tiles.offset + offsetof(gpu_data::CullTileListHeader, cullDispatch));
    commands.pass(commands.joinName(passName, "/draws"),
                  {gpu::use(scene_.cullMeshBuffer(), Usage::ComputeRead), gpu::use(scene_.materialBuffer(), Usage::ComputeRead),
                   gpu::use(listCounts_, Usage::ComputeRead), gpu::use(drawCommands_, Usage::ComputeWrite),
                   gpu::use(drawCounts_, Usage::ComputeWrite), gpu::use(tileStats_, Usage::ComputeWrite), tileArgs, tileReads});
    commands.bindPipeline(buildDraws_);
    using namespace gpu_data;
    const gpu::DescriptorWrite drawWrites[] = {
        {kCullBindingFrame, cullFrame},
        {kCullBindingMeshes, scene_.cullMeshBuffer(), {}, {}},
        {kCullBindingMaterials, scene_.materialBuffer(), {}, {}},
        {kCullBindingListCounts, listCounts_, {}, {}},
        {kDrawsBindingDrawCommands, drawCommands_, {}, {}},
        {kDrawsBindingDrawCounts, drawCounts_, {}, {}},
        {kDrawsBindingTileStats, tileStats_, {}, {}},
        {kCullBindingTiles, tiles}};
    commands.pushDescriptors(drawWrites);
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatchIndirect(tiles.buffer, tiles.offset + offsetof(gpu_data::CullTileListHeader, drawsDispatch));
}

const std::vector<gpu::DescriptorWrite>& ShadowCullingPass::cullWrites(const gpu::BufferSlice& cullFrame,
                                                                      const gpu::BufferSlice& tiles, gpu::BufferHandle pyramid) {
    using namespace gpu_data;
    writes_.assign({{kCullBindingFrame, cullFrame},
                    {kCullBindingTiles, tiles},
                    {kCullBindingInstances, scene_.cullInstanceBuffer(), {}, {}},
                    {kCullBindingMeshes, scene_.cullMeshBuffer(), {}, {}},
                    {kCullBindingMaterials, scene_.materialBuffer(), {}, {}},
                    {kCullBindingListCounts, listCounts_, {}, {}},
                    {kCullBindingViewHistory, viewHistory_, {}, {}},
                    {kCullBindingPyramid, pyramid, {}, {}},
                    {kCullBindingTileStats, tileStats_, {}, {}}});
    appendVisibleListWrites(writes_, kCullBindingVisibleInstances);
    return writes_;
}

const std::vector<gpu::ResourceUse>& ShadowCullingPass::cullUses(gpu::BufferHandle pyramid,
                                                                 std::initializer_list<gpu::ResourceUse> more) {
    using gpu::Usage;
    uses_.assign({gpu::use(scene_.cullInstanceBuffer(), Usage::ComputeRead), gpu::use(scene_.cullMeshBuffer(), Usage::ComputeRead),
                  gpu::use(scene_.materialBuffer(), Usage::ComputeRead), gpu::use(pyramid, Usage::ComputeRead),
                  gpu::use(listCounts_, Usage::ComputeWrite), gpu::use(viewHistory_, Usage::ComputeWrite),
                  gpu::use(tileStats_, Usage::ComputeWrite)});
    addVisibleListUses(uses_, Usage::ComputeWrite);
    uses_.insert(uses_.end(), more);
    return uses_;
}

gpu::BufferHandle ShadowCullingPass::visibleListBuffer(uint32_t tile) const {
    return visible_[gpu_data::visibleListBuffer(tile, listsPerBuffer_)];
}

void ShadowCullingPass::appendVisibleListWrites(std::vector<gpu::DescriptorWrite>& writes, uint32_t binding) const {
    for (uint32_t element = 0; element < gpu_data::kVisibleListBuffers; ++element) {
        gpu::DescriptorWrite& write = writes.emplace_back(binding, visible_[element < visibleBufferCount_ ? element : 0],
                                                          gpu::TextureHandle{}, gpu::SamplerHandle{});
        write.arrayElement = element;
    }
}

void ShadowCullingPass::addVisibleListUses(std::vector<gpu::ResourceUse>& uses, gpu::Usage usage) const {
    for (uint32_t b = 0; b < visibleBufferCount_; ++b) uses.push_back(gpu::use(visible_[b], usage));
}

void ShadowCullingPass::recordView(gpu::CommandList& commands, const gpu::BufferSlice& cullFrame, uint32_t phase,
                                   gpu::BufferHandle pyramid) {
    PENUMBRA_ASSERT(phase == gpu_data::kCullPassCameraEarly || phase == gpu_data::kCullPassCameraLate);
    PENUMBRA_ASSERT(tileCapacity_ <= gpu_data::kMaxCullTiles);  // else the camera's lists are tiles' lists
    commands.pass(phase == gpu_data::kCullPassCameraEarly ? "main/cull" : "main/cull late", cullUses(pyramid));
    commands.bindPipeline(cull_);
    // The main view reads no tile: its list binding is any buffer (the culling frame itself).
    commands.pushDescriptors(cullWrites(cullFrame, {viewHistory_, 0, 0}, pyramid));
    const gpu_data::CullConstants constants{phase, listsPerBuffer_, 0, 0};
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatch(groupsFor(scene_.instanceCount()), 1);
}

gpu::BufferSlice ShadowCullingPass::viewStats() const {
    return {tileStats_, gpu_data::kCullListCameraEarly * sizeof(gpu_data::CullTileStats),
            2 * sizeof(gpu_data::CullTileStats)};
}

ShadowCullingPass::DrawList ShadowCullingPass::drawList(uint32_t tile, uint32_t kind) const {
    const uint32_t list = tile * gpu_data::kCasterKinds + kind;
    DrawList draws;
    draws.commands = drawCommands_;
    draws.offset = uint64_t(list) * scene_.meshSlotCount() * kDrawCommandBytes;
    draws.count = drawCounts_;
    draws.countOffset = uint64_t(list) * 4;
    draws.maxDraws = scene_.meshSlotCount();
    return draws;
}

void ShadowCullingPass::addDrawUses(std::vector<gpu::ResourceUse>& uses) const {
    uses.push_back(gpu::use(drawCommands_, gpu::Usage::IndirectArguments));
    uses.push_back(gpu::use(drawCounts_, gpu::Usage::IndirectArguments));
    addVisibleListUses(uses, gpu::Usage::GraphicsRead);
}

std::vector<std::vector<uint32_t>> ShadowCullingPass::readVisibleLists(uint32_t tileCount) {
    auto words = [&](gpu::BufferHandle buffer) {
        const std::vector<uint8_t> bytes = device_.readBuffer(buffer);
        std::vector<uint32_t> values(bytes.size() / 4);
        std::memcpy(values.data(), bytes.data(), values.size() * 4);
        return values;
    };
    const std::vector<uint32_t> counts = words(listCounts_), meshes = words(scene_.cullMeshBuffer());
    std::vector<std::vector<uint32_t>> visible;
    for (uint32_t b = 0; b < visibleBufferCount_; ++b) visible.push_back(words(visible_[b]));
    const uint32_t meshCount = scene_.meshSlotCount(), instanceCount = std::max(scene_.instanceCount(), 1u);
    std::vector<std::vector<uint32_t>> lists(tileCount);
    for (uint32_t tile = 0; tile < tileCount; ++tile) {
        const std::vector<uint32_t>& buffer = visible[gpu_data::visibleListBuffer(tile, listsPerBuffer_)];
        const uint32_t start = gpu_data::visibleListStart(tile, listsPerBuffer_, instanceCount);
        for (uint32_t mesh = 0; mesh < meshCount; ++mesh) {
            constexpr size_t kStride = sizeof(gpu_data::CullMesh) / 4, kFirst = offsetof(gpu_data::CullMesh, firstListSlot) / 4;
            const uint32_t first = meshes[mesh * kStride + kFirst];  // CullMesh::firstListSlot
            for (uint32_t i = 0; i < counts[tile * meshCount + mesh]; ++i) lists[tile].push_back(buffer[start + first + i]);
        }
        std::sort(lists[tile].begin(), lists[tile].end());
    }
    return lists;
}

gpu::BufferSlice ShadowCullingPass::tileStats(uint32_t tileCount) const {
    return {tileStats_, 0, std::max<uint64_t>(tileCount, 1) * sizeof(gpu_data::CullTileStats)};
}

}  // namespace penumbra
