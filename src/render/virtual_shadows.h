#pragma once
// The renderer's virtual shadow maps (shadows.directional.mode = virtual): one VirtualShadowMap per
// reserved directional light, all in one VirtualPageStorageSet, so that the lit pass, the visibility
// resolve and the screen-space resolve bind three things whatever the light count
// (penumbra/shadows/virtual_shadows.glsl): the uniform VirtualDirectionalShadowData, the pools' texture and the
// page tables' buffer. With cascades the same bindings hold a disabled block and placeholders the
// shaders never read.
//
// A frame: beginFrame (maps for the settings and the light count, this frame's uniform slot), then
// appendLitInputs (the three bindings and their frame-graph reads) before the lit writes are used, then
// record once the view's depth is final and before anything shades (every light's mark -> page table
// -> draw -> mark drawn; no readback), then stats() for the frame-end readback.
//
// Invalidation (the published virtual shadow maps' caching: Unreal Engine's "Virtual Shadow Maps"
// documentation): a light whose direction changes or scene bounds that change redraw that light's map
// (VirtualShadowMap's draw space); casters that moved, appeared, disappeared or changed their cast flag
// pass their old and new world bounds (casterChanged), whose pages in every level are drawn again;
// more rectangles than one record holds, a material edit (alpha cut-outs) or shadows.virtual.cache =
// false redraw everything requested. A light that turns reads at movingLodBias (kVirtualMovingFrames).
#include <algorithm>
#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "penumbra/shadow_settings.h"
#include "render/main_pass.h"
#include "render/virtual_page_storage.h"
#include "render/virtual_shadow_map.h"
#include "shadows/shadow_planner.h"
#include "virtual_lit_structs.h"

namespace penumbra {

// A directional light whose direction changed in one of its last this many records reads at
// shadows.virtual.movingLodBias (Unreal Engine's r.Shadow.Virtual.ResolutionLodBiasDirectionalMoving):
// every page of a turning light is drawn again every frame, so finer texels would double that cost.
// Counting a few frames keeps a light that turns every other frame from flipping between the two.
constexpr uint32_t kVirtualMovingFrames = 4;

// Pages along a pool's side: a pool of `pages` (shadows.virtual.poolPages or facePoolPages) rounded down
// to a square (at least one page).
uint32_t virtualPoolPagesPerSide(uint32_t pages);

// The VirtualShadowMapConfig of the shadows.virtual settings (the pool rounded down to a square of pages).
VirtualShadowMapConfig virtualShadowMapConfig(const ShadowSettings& settings, const ShadowRasterOptions& raster);

// The most pages a side (up to poolPagesPerSide) whose pools fit the device for mapCount maps: their
// shared texture (mapCount pools stacked) within maxImageSize. (The rasterizer draws into a depth target
// of one record's pages: render/virtual_page_draw_pass.h.)
uint32_t fitVirtualPool(uint32_t poolPagesPerSide, uint32_t pageSize, uint32_t mapCount, uint32_t maxImageSize);

// One kind of virtual map's lit bindings (the directional maps', or the spot and point faces'): the
// binding numbers of its uniform block, pool and page table, and its index in
// MainPassInputs::virtualPages.
struct VirtualLitBindings {
    uint32_t block = 0, pool = 0, pages = 0;
    uint32_t table = 0;
};
// The three bindings into inputs.writes, the pool among inputs.sampled (before its last entry, which the
// screen-space resolve replaces) and the page table as inputs.virtualPages[bindings.table].
void appendVirtualLitInputs(MainPassInputs& inputs, const VirtualLitBindings& bindings, const gpu::BufferSlice& block,
                            gpu::TextureHandle pool, gpu::BufferHandle pages, gpu::SamplerHandle pointSampler);

class VirtualShadows {
public:
    VirtualShadows(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster);
    ~VirtualShadows();
    VirtualShadows(const VirtualShadows&) = delete;
    VirtualShadows& operator=(const VirtualShadows&) = delete;

    // Before a frame is recorded: the maps for these settings and `lightCount` reserved directional
    // lights when the mode is virtual (a changed configuration makes new ones: every page drawn again),
    // and this frame's uniform block (enabled or not). A pool larger than the device holds is shrunk,
    // with a warning.
    // oneShot: a frame of Renderer::render, which reads every light at lodBias (a still image's quality)
    // even right after the light turned.
    void beginFrame(const ShadowSettings& settings, uint32_t lightCount, const ShadowRasterOptions& raster, const CameraView& view,
                    bool oneShot, std::vector<std::string>& warnings);
    bool active() const { return active_; }

    // The three lit bindings into inputs.writes, the pool among inputs.sampled (before its last entry,
    // which the screen-space resolve replaces) and the page tables as inputs.storageRead.
    void appendLitInputs(MainPassInputs& inputs, gpu::SamplerHandle pointSampler) const;

    // A caster's world bounds before or after an edit: its pages are drawn again by the next record.
    void casterChanged(const Aabb& wsBounds);
    // The next record draws every requested page again (a material edit, new geometry).
    void invalidateAll() { invalidateAll_ = true; }

    // Records every reserved light's chain for the view whose depth `depth` holds; `plan` is this
    // frame's directional plan (the lights' directions and filters), wsSceneBounds the casters' bounds.
    // The rasterizer's counters after each map's pages are read back into rasterReadback[map]
    // (Device::readBackAtFrameEnd offsets; the maps share the rasterizer, so each is copied at once).
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& depth, const CameraView& view,
                const DirectionalShadowPlan& plan, const Aabb& wsSceneBounds, std::span<uint64_t> rasterReadback);

    // A settled frame (render/virtual_settling.h): no pass; the frame's uniform block gets the maps' lookup
    // data of their last record, which the page tables still hold.
    void keepPages(const DirectionalShadowPlan& plan);

    uint32_t mapCount() const { return uint32_t(maps_.size()); }
    // The maps a frame of lightCount reserved directional lights records and reads back: one per light
    // while there are maps, none when the mode is not virtual.
    uint32_t mapsInUse(uint32_t lightCount) const { return active_ ? std::min(mapCount(), lightCount) : 0u; }
    gpu::BufferSlice stats(uint32_t map) const { return maps_[map]->stats(); }
    gpu::BufferSlice levelStats(uint32_t map) const { return maps_[map]->levelStats(); }
    uint32_t levelCount() const { return config_.clipmap.levelCount; }
    uint32_t poolPages() const;  // physical pages of all the maps
    uint32_t pagesPerFrame() const;  // the most pages all the maps draw in a frame (their draw budgets)
    // Whether the light of a map in use by a frame of lightCount reserved directional lights changed
    // direction in one of its last kVirtualMovingFrames records: it reads at shadows.virtual.movingLodBias
    // until then. A settled frame (render/virtual_settling.h) records nothing, so frames must not settle
    // while this holds (the bias changes when it ends). Slots out of use do not count: their lights are
    // not recorded, so their count would never end.
    bool moving(uint32_t lightCount) const;

private:
    // Per shadow slot: the light's direction at its last record and the records since it changed.
    struct LightMotion {
        glm::vec3 wsDirection{0.0f};
        uint32_t framesStill = 0;
        bool known = false;
        bool turning() const { return known && framesStill < kVirtualMovingFrames; }
    };
    void noteDirection(uint32_t slot, const glm::vec3& wsDirection);
    // 2^lodBias, or 2^movingLodBias while the slot's light turns (not in a one-shot frame).
    float footprintScale(uint32_t slot) const;
    void configure(const VirtualShadowMapConfig& config, uint32_t lightCount);
    // The lights' lookup data into this frame's uniform slot.
    void publishLookupData(uint32_t lights);
    void releaseMaps();
    // The rectangles of the changed casters as `map` sees them this frame, into invalidations_; false
    // when they do not fit one record.
    bool collectInvalidations(const VirtualShadowMap& map, const CameraView& view);

    gpu::Device& device_;
    const GpuScene& scene_;
    ComputeRasterPass& raster_;
    VirtualShadowMapConfig config_;
    std::unique_ptr<VirtualPageStorageSet> storage_;
    std::vector<std::unique_ptr<VirtualShadowMap>> maps_;
    bool active_ = false, invalidateAll_ = false;
    gpu_data::VirtualDirectionalShadowData block_{};
    // slotCount_ uniform slots of the block (one per frame in flight + 1), each starting at a multiple
    // of the largest uniform offset alignment a device may ask.
    static constexpr uint64_t kSlotStride = gpu::portablyAligned(sizeof(gpu_data::VirtualDirectionalShadowData));
    uint64_t slotOffset() const { return uint64_t(slot_) * kSlotStride; }
    gpu::BufferHandle blocks_;
    uint32_t slotCount_ = 0, slot_ = 0;
    gpu::TextureHandle placeholderPool_;   // 1 x 1 R32F, never written: bound with cascades
    gpu::BufferHandle placeholderPages_;   // one VirtualPageEntry, never written
    std::vector<Aabb> changedBounds_;      // since the last record (capacity kept)
    std::array<LevelPageRect, gpu_data::kVirtualPageMaxLevels> levelRects_{};
    std::array<gpu_data::VirtualPageInvalidation, VirtualShadowMap::kMaxInvalidations> invalidations_{};
    uint32_t invalidationCount_ = 0;
    std::array<LightMotion, gpu_data::kMaxShadowedDirectionalLights> motion_{};  // by shadow slot
    float stillScale_ = 1.0f, movingScale_ = 1.0f;  // 2^lodBias, 2^movingLodBias
    bool oneShot_ = false;
};

}  // namespace penumbra
