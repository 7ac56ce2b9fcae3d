#include "render/virtual_shadows.h"

#include <algorithm>
#include <cmath>

#include "pass_bindings.h"
#include "shadows/cascades.h"
#include "shadows/shadow_gpu_packing.h"
#include "shadows/virtual_page_marking.h"

namespace penumbra {

uint32_t virtualPoolPagesPerSide(uint32_t pages) {
    return std::max(1u, uint32_t(std::floor(std::sqrt(double(pages)))));
}

VirtualShadowMapConfig virtualShadowMapConfig(const ShadowSettings& settings, const ShadowRasterOptions& raster) {
    const VirtualShadowSettings& pages = settings.virtualMaps;
    VirtualShadowMapConfig config;
    config.clipmap.resolution = pages.resolution;
    config.clipmap.pageSize = pages.pageSize;
    config.clipmap.levelCount = pages.levelCount;
    config.clipmap.firstLevelSize = pages.firstLevelSize;
    config.poolPagesPerSide = virtualPoolPagesPerSide(pages.poolPages);
    config.keepFrames = pages.keepFrames;
    config.raster = raster;
    return config;
}

namespace {

bool sameConfig(const VirtualShadowMapConfig& a, const VirtualShadowMapConfig& b) {
    return a.clipmap.resolution == b.clipmap.resolution && a.clipmap.pageSize == b.clipmap.pageSize &&
           a.clipmap.levelCount == b.clipmap.levelCount && a.clipmap.firstLevelSize == b.clipmap.firstLevelSize &&
           a.poolPagesPerSide == b.poolPagesPerSide && a.keepFrames == b.keepFrames && a.raster == b.raster;
}

}  // namespace

VirtualShadows::VirtualShadows(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster)
    : device_(device), scene_(gpuScene), raster_(raster) {
    slotCount_ = device.framesInFlight() + 1;  // a slot is free again once its next frame begins
    try {
        blocks_ = device.createBuffer(kSlotStride * slotCount_, gpu::kBufferUniform, gpu::MemoryKind::HostVisible,
                                      nullptr, "virtual shadow lit blocks");
        placeholderPool_ = device.createTexture({1, 1, gpu::Format::R32Float, gpu::kTextureSampled, 1, "no virtual pool"});
        placeholderPages_ = device.createBuffer(sizeof(gpu_data::VirtualPageEntry), gpu::kBufferStorage,
                                                gpu::MemoryKind::DeviceLocal, nullptr, "no virtual page table");
    } catch (...) {  // the destructor does not run
        device.destroy(blocks_);
        device.destroy(placeholderPool_);
        throw;
    }
    changedBounds_.reserve(VirtualShadowMap::kMaxInvalidations);
}

VirtualShadows::~VirtualShadows() {
    releaseMaps();
    device_.destroy(blocks_);
    device_.destroy(placeholderPool_);
    device_.destroy(placeholderPages_);
}

void VirtualShadows::releaseMaps() {
    maps_.clear();  // before the storage they draw into
    storage_.reset();
    motion_ = {};
}

void VirtualShadows::noteDirection(uint32_t slot, const glm::vec3& wsDirection) {
    LightMotion& m = motion_[slot];
    if (!m.known) {
        m = {wsDirection, kVirtualMovingFrames, true};  // a light that appears is still
    } else if (wsDirection != m.wsDirection) {
        m.wsDirection = wsDirection;
        m.framesStill = 0;
    } else if (m.framesStill < kVirtualMovingFrames) {
        ++m.framesStill;
    }
}

float VirtualShadows::footprintScale(uint32_t slot) const {
    return !oneShot_ && motion_[slot].turning() ? movingScale_ : stillScale_;
}

bool VirtualShadows::moving(uint32_t lightCount) const {
    for (uint32_t slot = 0; slot < mapsInUse(lightCount); ++slot)
        if (motion_[slot].turning()) return true;
    return false;
}

uint32_t VirtualShadows::poolPages() const {
    return uint32_t(maps_.size()) * config_.poolPagesPerSide * config_.poolPagesPerSide;
}

uint32_t VirtualShadows::pagesPerFrame() const {
    uint32_t pages = 0;
    for (const auto& map : maps_) pages += map->pagesPerFrame();
    return pages;
}

void VirtualShadows::configure(const VirtualShadowMapConfig& config, uint32_t lightCount) {
    if (!maps_.empty() && sameConfig(config, config_) && maps_.size() >= lightCount) return;
    releaseMaps();
    config_ = config;
    if (lightCount == 0) return;
    storage_ = std::make_unique<VirtualPageStorageSet>(device_, config.clipmap, config.poolPagesPerSide, lightCount);
    for (uint32_t i = 0; i < lightCount; ++i) {
        const VirtualPageStorage storage = storage_->storageFor(i);
        maps_.push_back(std::make_unique<VirtualShadowMap>(device_, scene_, raster_, config, &storage));
    }
}

uint32_t fitVirtualPool(uint32_t poolPagesPerSide, uint32_t pageSize, uint32_t mapCount, uint32_t maxImageSize) {
    uint32_t side = poolPagesPerSide;
    while (side > 1 && uint64_t(side) * pageSize * std::max(mapCount, 1u) > maxImageSize) --side;
    return side;
}

void VirtualShadows::beginFrame(const ShadowSettings& settings, uint32_t lightCount, const ShadowRasterOptions& raster,
                                const CameraView& view, bool oneShot, std::vector<std::string>& warnings) {
    active_ = settings.directional.mode == DirectionalShadowMode::Virtual;
    if (active_) {
        VirtualShadowMapConfig config = virtualShadowMapConfig(settings, raster);
        const uint32_t requested = config.poolPagesPerSide;
        config.poolPagesPerSide = fitVirtualPool(requested, config.clipmap.pageSize, lightCount, device_.maxImageSize());
        if (config.poolPagesPerSide < requested)
            warnings.push_back("shadows.virtual.poolPages = " + std::to_string(settings.virtualMaps.poolPages) + " for " +
                               std::to_string(lightCount) + " directional lights is more than " + device_.info().name +
                               " holds; using " + std::to_string(config.poolPagesPerSide * config.poolPagesPerSide) +
                               " pages per light");
        configure(config, lightCount);
        if (!settings.virtualMaps.cache) invalidateAll_ = true;
        for (const auto& map : maps_) map->setPagesPerFrame(settings.virtualMaps.pagesPerFrame);
    } else if (!maps_.empty()) {
        releaseMaps();  // deferred by the device until the frames using them are done
    }
    slot_ = (slot_ + 1) % slotCount_;
    block_ = {};
    block_.enabled = active_ ? 1u : 0u;
    block_.wsFootprintPerDepth = wsFootprintPerDepth(view);
    stillScale_ = std::exp2(settings.virtualMaps.lodBias);
    movingScale_ = std::exp2(settings.virtualMaps.movingLodBias);
    oneShot_ = oneShot;
    device_.writeBuffer(blocks_, &block_, sizeof(block_), slotOffset());
}

void VirtualShadows::appendLitInputs(MainPassInputs& inputs, gpu::SamplerHandle pointSampler) const {
    using namespace gpu_data;
    const bool bound = active_ && storage_;
    const gpu::TextureHandle pool = bound ? storage_->poolTexture() : placeholderPool_;
    const gpu::BufferHandle pages = bound ? storage_->entries() : placeholderPages_;
    appendVirtualLitInputs(inputs, {kLitBindingVirtualShadows, kLitBindingVirtualPool, kLitBindingVirtualPages, 0},
                           {blocks_, slotOffset(), sizeof(block_)}, pool, pages, pointSampler);
}

void appendVirtualLitInputs(MainPassInputs& inputs, const VirtualLitBindings& bindings, const gpu::BufferSlice& block,
                            gpu::TextureHandle pool, gpu::BufferHandle pages, gpu::SamplerHandle pointSampler) {
    inputs.writes.push_back({bindings.block, block});
    inputs.writes.push_back({bindings.pool, {}, pool, pointSampler});
    inputs.writes.push_back({bindings.pages, pages, {}, {}});
    // Before the last sampled texture: the screen-space resolve replaces that one.
    inputs.sampled.insert(inputs.sampled.empty() ? inputs.sampled.end() : inputs.sampled.end() - 1, pool);
    inputs.virtualPages[bindings.table] = pages;
}

void VirtualShadows::casterChanged(const Aabb& wsBounds) {
    if (!active_ || !wsBounds.valid()) return;
    if (changedBounds_.size() >= VirtualShadowMap::kMaxInvalidations) {  // too many to track: redraw all
        invalidateAll_ = true;
        return;
    }
    changedBounds_.push_back(wsBounds);
}

bool VirtualShadows::collectInvalidations(const VirtualShadowMap& map, const CameraView& view) {
    invalidationCount_ = 0;
    const glm::mat4& lightRotation = map.drawSpace().lightRotationFromWorld;
    const glm::vec2 lsCamera = lsClipmapCentre(lightRotation, view);
    for (const Aabb& bounds : changedBounds_) {
        const uint32_t count = casterPageRects(config_.clipmap, lightRotation, lsCamera, bounds, levelRects_.data());
        if (invalidationCount_ + count > invalidations_.size()) return false;
        for (uint32_t i = 0; i < count; ++i)
            invalidations_[invalidationCount_++] = virtualPageInvalidation(levelRects_[i].level, levelRects_[i].pages);
    }
    return true;
}

void VirtualShadows::record(gpu::CommandList& commands, const VirtualPageDepthSource& depth, const CameraView& view,
                            const DirectionalShadowPlan& plan, const Aabb& wsSceneBounds,
                            std::span<uint64_t> rasterReadback) {
    if (!active_) return;
    const uint32_t lights = mapsInUse(uint32_t(plan.lights.size()));
    for (uint32_t slot = 0; slot < lights; ++slot) {
        VirtualShadowMap& map = *maps_[slot];
        const gpu_data::DirectionalShadowLight& light = plan.gpu.lights[slot];
        // The draw space of the last record: a new light direction invalidates everything anyway.
        if (invalidateAll_ || !collectInvalidations(map, view)) {
            map.invalidateAll();
            invalidationCount_ = 0;
        }
        // The marking's margin: the reach of the light's lookups, as the cascades' tight fit keeps it.
        const float marginTexels =
            lookupReachTexels(light.normalBias, light.pcssTanRadius > 0.0f, ShadowFilter(light.filterMode));
        noteDirection(slot, plan.lights[slot].wsDirection);
        map.record(commands, depth, view, plan.lights[slot].wsDirection, wsSceneBounds, marginTexels,
                   std::span(invalidations_.data(), invalidationCount_), footprintScale(slot));
        if (slot < rasterReadback.size()) rasterReadback[slot] = device_.readBackAtFrameEnd(commands, raster_.counters());
    }
    invalidateAll_ = false;
    changedBounds_.clear();
    publishLookupData(lights);
}

void VirtualShadows::keepPages(const DirectionalShadowPlan& plan) {
    if (active_) publishLookupData(mapsInUse(uint32_t(plan.lights.size())));
}

void VirtualShadows::publishLookupData(uint32_t lights) {
    block_.mapCount = lights;
    for (uint32_t slot = 0; slot < lights; ++slot) {
        block_.maps[slot] = maps_[slot]->lookupData();
        block_.footprintScales[int(slot)] = footprintScale(slot);  // what its last record marked with
    }
    device_.writeBuffer(blocks_, &block_, sizeof(block_), slotOffset());
}

}  // namespace penumbra
