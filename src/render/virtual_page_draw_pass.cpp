#include "render/virtual_page_draw_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"
#include "shadows/cascades.h"
#include "shadows/cull_packing.h"

namespace penumbra {

namespace {

using gpu::Usage;

uint32_t groupsOf(uint32_t count, uint32_t group) { return (count + group - 1) / group; }

}  // namespace

VirtualPageDrawSpace makeVirtualPageDrawSpace(const VirtualClipmapConfig& clipmap, const glm::vec3& wsLightDirection,
                                              const Aabb& wsSceneBounds) {
    VirtualPageDrawSpace space;
    space.clipmap = clipmap;
    space.lightRotationFromWorld = clipmapRotationFromWorld(wsLightDirection);
    const Aabb lsBounds = wsSceneBounds.valid() ? wsSceneBounds.transformed(space.lightRotationFromWorld) : Aabb{};
    const float zMin = lsBounds.valid() ? lsBounds.min.z : -1.0f, zMax = lsBounds.valid() ? lsBounds.max.z : 1.0f;
    const float margin = 0.01f * (zMax - zMin) + 0.01f;
    space.lsDepthNear = zMax + margin;  // the light travels along -z: the largest z is nearest to it
    space.lsDepthFar = zMin - margin;
    return space;
}

glm::mat4 virtualPageClipFromWorld(const VirtualPageDrawSpace& space, uint32_t level, const glm::ivec2& page) {
    // Operation for operation as virtual_page_tiles.comp pageTile.
    const uint32_t pagesPerSide = penumbra::pagesPerSide(space.clipmap);
    const float lsPage = space.clipmap.firstLevelSize * std::exp2(float(level)) / float(pagesPerSide);
    const float near = space.lsDepthNear, far = space.lsDepthFar;
    glm::mat4 clipFromLight(1.0f);
    clipFromLight[0] = glm::vec4(2.0f / lsPage, 0.0f, 0.0f, 0.0f);
    clipFromLight[1] = glm::vec4(0.0f, 2.0f / lsPage, 0.0f, 0.0f);
    clipFromLight[2] = glm::vec4(0.0f, 0.0f, -1.0f / (near - far), 0.0f);
    clipFromLight[3] = glm::vec4(-2.0f * glm::vec2(page) - 1.0f, near / (near - far), 1.0f);
    return clipFromLight * space.lightRotationFromWorld;
}

uint32_t virtualPagesPerRecord(uint32_t poolPages, uint32_t instanceCount, uint64_t listBytes) {
    // The culling pass keeps the main view's lists besides its tiles' (unused here).
    constexpr uint64_t kViewLists = ShadowCullingPass::kViewLists;
    const uint64_t lists = listBytes / (uint64_t(std::max(instanceCount, 1u)) * 4);
    const uint64_t pages = lists > kViewLists ? lists - kViewLists : 0;
    const uint32_t most = std::min(poolPages, kMaxVirtualPagesPerRecord);
    return uint32_t(std::clamp<uint64_t>(pages, std::min(kMinVirtualPagesPerRecord, most), most));
}

uint32_t virtualDrawTargetPagesPerSide(uint32_t pagesPerRecord) {
    uint32_t side = 1;
    while (side * side < pagesPerRecord) ++side;
    return side;
}

namespace {

// virtualPagesPerRecord within the lists the device's storage buffers hold (fewer than the culling pass
// needs: it refuses the scene in one line) and a depth target that one storage buffer holds.
uint32_t pagesPerRecordOn(const gpu::Device& device, uint32_t instanceCount, uint32_t poolPages, uint32_t pageSize) {
    const uint64_t deviceLists = maxVisibleLists(instanceCount, device.maxStorageBufferRange(), visibleListBuffersOn(device));
    constexpr uint64_t kViewLists = ShadowCullingPass::kViewLists;
    uint32_t pages = virtualPagesPerRecord(poolPages, instanceCount, kVirtualPageListBytes);
    if (deviceLists > kViewLists) pages = uint32_t(std::min<uint64_t>(pages, deviceLists - kViewLists));
    const auto targetBytes = [&](uint32_t n) {
        const uint64_t side = uint64_t(virtualDrawTargetPagesPerSide(n)) * pageSize;
        return side * side * 4;
    };
    while (pages > 1 && targetBytes(pages) > device.maxStorageBufferRange()) --pages;
    return pages;
}

}  // namespace

gpu::Rect virtualPageRect(uint32_t index, uint32_t pagesPerSide, uint32_t pageSize) {
    return {int32_t(index % pagesPerSide * pageSize), int32_t(index / pagesPerSide * pageSize), pageSize, pageSize};
}

VirtualPageDrawPass::VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                                         const VirtualClipmapConfig& clipmap, uint32_t poolPagesPerSide,
                                         const VirtualPageStorage* shared)
    : VirtualPageDrawPass(device, gpuScene, raster, clipmap.pageSize, pagesPerSide(clipmap), poolPagesPerSide, false, shared) {}

VirtualPageDrawPass::VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                                         const VirtualFaceConfig& faces, uint32_t poolPagesPerSide)
    : VirtualPageDrawPass(device, gpuScene, raster, faces.pageSize, virtualFacePagesPerSide(faces), poolPagesPerSide, true,
                          nullptr) {}

VirtualPageDrawPass::VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                                         uint32_t pageSize, uint32_t pagesPerLevelSide, uint32_t poolPagesPerSide, bool faces,
                                         const VirtualPageStorage* shared)
    : device_(device), scene_(gpuScene), raster_(raster), poolPagesPerSide_(poolPagesPerSide), pageSize_(pageSize),
      pagesPerLevelSide_(pagesPerLevelSide),
      pagesPerRecord_(pagesPerRecordOn(device, gpuScene.instanceCount(), std::max(poolPagesPerSide * poolPagesPerSide, 1u),
                                       std::max(pageSize, 1u))),
      targetPagesPerSide_(virtualDrawTargetPagesPerSide(pagesPerRecord_)), faces_(faces), culling_(device, gpuScene, pagesPerRecord_) {
    if (poolPagesPerSide == 0 || pageSize_ == 0 || uint64_t(poolPagesPerSide) * pageSize_ > device.maxImageSize())
        throw Error("internal: a virtual page pool of " + std::to_string(poolPagesPerSide) + "^2 pages of " +
                    std::to_string(pageSize_) + " texels does not fit an image");
    poolFormat_ = virtualPoolFormat(device);
    if (shared && shared->poolTexture) useSharedTexture(*shared);
    try {
        create();
    } catch (...) {
        release();  // a failed allocation half-way: the destructor does not run
        throw;
    }
}

VirtualPageDrawPass::~VirtualPageDrawPass() { release(); }

void VirtualPageDrawPass::useSharedTexture(const VirtualPageStorage& shared) {
    const gpu::TextureDesc& desc = device_.textureDesc(shared.poolTexture);
    const uint32_t needed = gpu::kTextureSampled | gpu::kTextureStorage;
    const bool format = desc.format == gpu::Format::R16Unorm || desc.format == gpu::Format::R32Float;
    if (!format || (desc.usage & needed) != needed || desc.width != poolSide() ||
        uint64_t(shared.poolOriginY) + poolSide() > desc.height)
        throw Error("internal: a shared virtual page pool texture of " + std::to_string(desc.width) + " x " +
                    std::to_string(desc.height) + " texels holds no pool of " + std::to_string(poolSide()) +
                    " texels at row " + std::to_string(shared.poolOriginY));
    poolTexture_ = shared.poolTexture;
    poolFormat_ = desc.format;
    poolOriginY_ = shared.poolOriginY;
    ownsTexture_ = false;
}

void VirtualPageDrawPass::release() {
    for (gpu::PipelineHandle p : {tilesPipeline_, copyPipeline_}) device_.destroy(p);
    for (gpu::BufferHandle b : {cullFrame_, tiles_, rasterList_, targetDepth_}) device_.destroy(b);
    if (ownsTexture_) device_.destroy(poolTexture_);  // a shared texture is its storage's
}

void VirtualPageDrawPass::create() {
    gpu::ComputePipelineDesc desc;
    desc.shader = desc.debugName = faces_ ? "virtual_face_tiles.comp" : "virtual_page_tiles.comp";
    desc.bindings = virtualPageDrawBindings(desc.shader);
    desc.pushConstantSize = sizeof(gpu_data::VirtualPageTilesConstants);
    tilesPipeline_ = device_.createComputePipeline(desc);
    // The copy's storage image format is the pool's (virtual_page_structs.h, "The pool's texels").
    desc.shader = desc.debugName = poolFormat_ == gpu::Format::R16Unorm ? "virtual_page_copy.comp" : "virtual_page_copy_r32f.comp";
    desc.bindings = virtualPageDrawBindings(desc.shader);
    desc.pushConstantSize = sizeof(gpu_data::VirtualPageCopyConstants);
    copyPipeline_ = device_.createComputePipeline(desc);

    // The pages' culling frame: the counts; no cascade spheres (pages do no blend culling).
    gpu_data::CullFrame frame{};
    frame.instanceCount = scene_.instanceCount();
    frame.meshCount = scene_.meshSlotCount();
    using gpu::MemoryKind;
    cullFrame_ = device_.createBuffer(sizeof(frame), gpu::kBufferUniform, MemoryKind::DeviceLocal, &frame,
                                      "virtual page culling frame");
    const uint64_t pages = pagesPerRecord_;
    tiles_ = device_.createBuffer(sizeof(gpu_data::CullTileListHeader) + pages * sizeof(gpu_data::CullTile),
                                  gpu::kBufferStorage | gpu::kBufferIndirect, MemoryKind::DeviceLocal, nullptr,
                                  "virtual page cull tiles");
    rasterList_ = device_.createBuffer(sizeof(gpu_data::RasterTileListHeader) + pages * 4,
                                       gpu::kBufferStorage | gpu::kBufferIndirect, MemoryKind::DeviceLocal, nullptr,
                                       "virtual page raster list");
    // The depth target: every slot is cleared to far before it is drawn (the rasterizer's clear step).
    const uint64_t targetSide = uint64_t(targetPagesPerSide_) * pageSize_;
    targetDepth_ = device_.createBuffer(targetSide * targetSide * 4, gpu::kBufferStorage, MemoryKind::DeviceLocal, nullptr,
                                        "virtual page depth target");
    if (!ownsTexture_) return;  // a shared texture starts far already (VirtualPageStorageSet)
    poolTexture_ = device_.createTexture(virtualPoolTextureDesc(poolFormat_, poolSide(), poolSide(), gpu::kTextureTransferDst,
                                                                "virtual page pool"));
    fillVirtualPoolTextureFar(device_, poolTexture_);  // the image starts far
}

void VirtualPageDrawPass::record(gpu::CommandList& commands, const VirtualPageDrawInputs& inputs) {
    PENUMBRA_ASSERT(inputs.drawList && inputs.entries.buffer && (faces_ ? inputs.faceCount > 0 && inputs.faces.buffer
                                                                       : inputs.space != nullptr));
    PENUMBRA_ASSERT(faces_ || (inputs.space->clipmap.pageSize == pageSize_ && pagesPerSide(inputs.space->clipmap) == pagesPerLevelSide_));
    using namespace gpu_data;
    const uint64_t tileBytes = device_.bufferSize(tiles_), listBytes = device_.bufferSize(rasterList_);
    // GPU timers per kind of map, so the faces' draws and the clipmaps' are told apart.
    const std::string_view timers = faces_ ? "virtualFacePages" : "virtualPages";
    commands.beginTimer(faces_ ? "virtualFacePages/cull" : "virtualPages/cull");
    // 1. The draw list -> tile lists (one thread per page the lists can hold: the count is the GPU's).
    const gpu::ResourceUse tileUses[] = {gpu::use(inputs.drawList, Usage::ComputeRead), gpu::use(tiles_, Usage::ComputeWrite),
                                         gpu::use(rasterList_, Usage::ComputeWrite),
                                         gpu::use(inputs.faces.buffer, Usage::ComputeRead)};
    commands.pass("virtualPages.tiles", std::span(tileUses, faces_ ? 4 : 3));
    commands.bindPipeline(tilesPipeline_);
    const gpu::DescriptorWrite tileWrites[] = {{kPageDrawBindingDrawList, inputs.drawList, {}, {}},
                                               {kPageDrawBindingTiles, tiles_, {}, {}},
                                               {kPageDrawBindingRasterList, rasterList_, {}, {}},
                                               {kPageDrawBindingFaces, inputs.faces}};
    commands.pushDescriptors(std::span(tileWrites, faces_ ? 4 : 3));
    VirtualPageTilesConstants constants{};
    if (!faces_) {
        const VirtualPageDrawSpace& space = *inputs.space;
        constants.lightRotationFromWorld = space.lightRotationFromWorld;
        constants.lsDepthNear = space.lsDepthNear;
        constants.lsDepthFar = space.lsDepthFar;
        constants.firstLevelSize = space.clipmap.firstLevelSize;
        constants.slopeBias = space.slopeBias;
    }
    constants.faceCount = inputs.faceCount;
    constants.pagesPerSide = pagesPerLevelSide_;
    constants.pageSize = pageSize_;
    constants.targetPagesPerSide = targetPagesPerSide_;
    constants.capacity = pagesPerRecord_;
    constants.instanceGroups = groupsOf(scene_.instanceCount(), kCullWorkgroupSize);
    constants.meshGroups = groupsOf(scene_.meshSlotCount(), kCullWorkgroupSize);
    constants.expandGroups = groupsOf(scene_.instanceCount(), kRasterExpandGroup);
    commands.pushConstants(&constants, sizeof(constants));
    commands.dispatch(groupsOf(pagesPerRecord_, kVirtualPageGroupSize), 1);
    // 2. Culling per page, 3. clear and raster per page (both sized by the lists' headers).
    culling_.record(commands, {cullFrame_, 0, sizeof(CullFrame)}, {tiles_, 0, tileBytes}, "virtualPages.culling");
    commands.endTimer();
    const RasterTileLists lists{{cullFrame_, 0, sizeof(CullFrame)}, {tiles_, 0, tileBytes}, {rasterList_, 0, listBytes}};
    sceneWrites_.clear();  // the scene's buffers may be new since the last record
    sceneWrites_.push_back({kSceneBindingVertices, scene_.vertexBuffer(), {}, {}});
    sceneWrites_.push_back({kSceneBindingInstances, scene_.instanceBuffer(), {}, {}});
    sceneWrites_.push_back({kSceneBindingMaterials, scene_.materialBuffer(), {}, {}});
    raster_.recordTiles(commands, sceneWrites_, lists, culling_, targetDepth_, targetPagesPerSide_ * pageSize_,
                        inputs.raster, timers);
    // 4. The slots into their physical pages of the sampled image, one workgroup per page (the list's pageDispatch).
    // Each page's depth range goes into its entry (the table's entries: this map's range of them).
    commands.beginTimer(faces_ ? "virtualFacePages/copy" : "virtualPages/copy");
    commands.pass("virtualPages/copy", {gpu::use(inputs.drawList, Usage::IndirectArguments),
                                        gpu::use(inputs.drawList, Usage::ComputeRead), gpu::use(targetDepth_, Usage::ComputeRead),
                                        gpu::use(poolTexture_, Usage::ComputeWrite), gpu::use(inputs.entries.buffer, Usage::ComputeWrite)});
    commands.bindPipeline(copyPipeline_);
    const gpu::DescriptorWrite copyWrites[] = {{kPageDrawBindingDrawList, inputs.drawList, {}, {}},
                                               {kPageDrawBindingTargetDepth, targetDepth_, {}, {}},
                                               {kPageDrawBindingPoolTexture, {}, poolTexture_, {}},
                                               {kPageDrawBindingEntries, inputs.entries}};
    commands.pushDescriptors(copyWrites);
    const VirtualPageCopyConstants copy{pageSize_, poolPagesPerSide_, pagesPerRecord_, poolOriginY_, targetPagesPerSide_};
    commands.pushConstants(&copy, sizeof(copy));
    commands.dispatchIndirect(inputs.drawList, offsetof(VirtualPageDrawHeader, pageDispatch));
    commands.endTimer();
}

}  // namespace penumbra
