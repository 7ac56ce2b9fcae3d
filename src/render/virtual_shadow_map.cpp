#include "render/virtual_shadow_map.h"

#include <cstring>

#include "core/error.h"
#include "pass_bindings.h"
#include "shadows/virtual_page_marking.h"
#include "shadows/virtual_shadow_lookup.h"

namespace penumbra {

namespace {

bool sameBounds(const Aabb& a, const Aabb& b) {
    if (a.valid() != b.valid()) return false;
    return !a.valid() || (a.min == b.min && a.max == b.max);
}

}  // namespace

VirtualShadowMap::VirtualShadowMap(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                                   const VirtualShadowMapConfig& config, const VirtualPageStorage* storage)
    : device_(device), scene_(gpuScene), config_(config), mark_(device),
      table_(device, config.clipmap, config.poolPagesPerSide * config.poolPagesPerSide, config.keepFrames, storage),
      draw_(device, gpuScene, raster, config.clipmap, config.poolPagesPerSide, storage) {
    setPagesPerFrame(0);
    slotCount_ = device.framesInFlight() + 1;  // a frame's slot is free again once its slot's next frame begins
    uploads_ = device.createBuffer(slotLayout().size * slotCount_, gpu::kBufferUniform | gpu::kBufferStorage,
                                   gpu::MemoryKind::HostVisible, nullptr, "virtual shadow map uploads");
}

VirtualShadowMap::~VirtualShadowMap() { device_.destroy(uploads_); }

VirtualShadowMap::SlotLayout VirtualShadowMap::slotLayout() {
    SlotLayout layout;
    layout.mark = 0;
    layout.table = layout.mark + gpu::portablyAligned(sizeof(gpu_data::VirtualPageMarkData));
    layout.lookup = layout.table + gpu::portablyAligned(sizeof(gpu_data::VirtualPageTableData));
    layout.invalidations = layout.lookup + gpu::portablyAligned(sizeof(gpu_data::VirtualShadowLookupData));
    layout.size = layout.invalidations + gpu::portablyAligned(kMaxInvalidations * sizeof(gpu_data::VirtualPageInvalidation));
    return layout;
}

uint32_t VirtualShadowMap::pageEntryCount() const {
    const uint32_t side = pagesPerSide(config_.clipmap);
    return config_.clipmap.levelCount * side * side;
}

gpu_data::VirtualPageStats VirtualShadowMap::statsFromReadback(const uint8_t* bytes) {
    gpu_data::VirtualPageStats stats{};
    std::memcpy(&stats, bytes, sizeof(stats));
    return stats;
}

bool VirtualShadowMap::updateDrawSpace(const glm::vec3& wsLightDirection, const Aabb& wsSceneBounds) {
    if (hasSpace_ && wsLightDirection == wsLightDirection_ && sameBounds(wsSceneBounds, wsSceneBounds_)) return false;
    space_ = makeVirtualPageDrawSpace(config_.clipmap, wsLightDirection, wsSceneBounds);
    wsLightDirection_ = wsLightDirection;
    wsSceneBounds_ = wsSceneBounds;
    hasSpace_ = true;
    return true;
}

void VirtualShadowMap::record(gpu::CommandList& commands, const VirtualPageDepthSource& mainDepth, const CameraView& view,
                              const glm::vec3& wsLightDirection, const Aabb& wsSceneBounds, float marginTexels,
                              std::span<const gpu_data::VirtualPageInvalidation> invalidations, float footprintScale) {
    const bool newSpace = updateDrawSpace(wsLightDirection, wsSceneBounds);
    const bool tooMany = invalidations.size() > kMaxInvalidations;
    const bool invalidateAll = newSpace || forceInvalidate_ || tooMany;
    const uint32_t rectangles = invalidateAll ? 0u : uint32_t(invalidations.size());
    forceInvalidate_ = false;
    lastInvalidatedAll_ = invalidateAll;

    // This record's uniform data and rectangles, in the next slot (its last reader has finished).
    const SlotLayout layout = slotLayout();
    const uint64_t base = uint64_t(nextSlot_) * layout.size;
    nextSlot_ = (nextSlot_ + 1) % slotCount_;
    const glm::mat4& lightFromWorld = space_.lightRotationFromWorld;
    const glm::vec2 lsCamera = lsClipmapCentre(lightFromWorld, view);
    gpu_data::VirtualPageMarkData mark = packVirtualPageMark(config_.clipmap, lightFromWorld, view, marginTexels);
    mark.wsFootprintPerDepth *= footprintScale;
    const gpu_data::VirtualPageTableData tableData = table_.packFrame(lsCamera, invalidateAll, rectangles);
    lookup_ = packVirtualShadowLookup(config_.clipmap, lightFromWorld, space_.lsDepthNear, space_.lsDepthFar, lsCamera,
                                      config_.poolPagesPerSide, draw_.poolOriginY(), table_.firstEntry());
    device_.writeBuffer(uploads_, &mark, sizeof(mark), base + layout.mark);
    device_.writeBuffer(uploads_, &tableData, sizeof(tableData), base + layout.table);
    device_.writeBuffer(uploads_, &lookup_, sizeof(lookup_), base + layout.lookup);
    if (rectangles > 0)
        device_.writeBuffer(uploads_, invalidations.data(), rectangles * sizeof(invalidations[0]), base + layout.invalidations);
    lookupSlice_ = {uploads_, base + layout.lookup, sizeof(lookup_)};

    // 1. Marking, 2. the table update, 3. drawing the dirty pages, 4. marking them drawn.
    commands.beginTimer("virtualPages/mark");
    mark_.record(commands, mainDepth, {uploads_, base + layout.mark, sizeof(mark)}, config_.clipmap);
    commands.endTimer();
    const gpu::BufferSlice invalidationSlice{uploads_, base + layout.invalidations,
                                             kMaxInvalidations * sizeof(gpu_data::VirtualPageInvalidation)};
    commands.beginTimer("virtualPages/table");
    table_.record(commands, {mark_.requestWords(), {uploads_, base + layout.table, sizeof(tableData)}, invalidationSlice,
                             rectangles});
    commands.endTimer();
    draw_.record(commands, {table_.drawList(), table_.entriesSlice(), &space_, config_.raster, {}, 0});
    commands.beginTimer("virtualPages/drawn");
    table_.recordMarkDrawn(commands);
    commands.endTimer();
}

}  // namespace penumbra
