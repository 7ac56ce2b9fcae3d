#pragma once
// One directional light's virtual shadow map: the whole chain of a frame in one command list, with no
// CPU readback. Per record, from the main view's depth:
//   1. virtualPages/mark      the request bits of the pages the view's lookups read (VirtualPageMarkPass);
//   2. virtualPageTable/...   the page table update: frees, caches, allocates, the dirty pages' draw list
//                             (VirtualPageTablePass);
//   3. virtualPages...        the listed pages drawn into the pool (VirtualPageDrawPass);
//   4. virtualPageTable/drawn those pages are no longer dirty: the lookups may read them.
// Afterwards a lit pass samples pageEntries(), poolTexture() and lookupData() (shaders/
// penumbra/shadows/virtual_shadow_lookup.glsl) after declaring its reads; stats() is the update's VirtualPageStats, for
// Device::readBackAtFrameEnd (statsFromReadback decodes it).
//
// Invalidation: the pages' depth is relative to the light's rotation and the scene bounds' depth range
// (makeVirtualPageDrawSpace), so a light whose direction changes, or bounds that change, make a new draw
// space and every resident page dirty: the requested ones are drawn again in the same record, the others
// are not sampled until a later request draws them. Casters that moved pass the page rectangles they
// covered before and cover now (virtualPageInvalidation over pagesTouchedByBounds of each level); more than
// kMaxInvalidations rectangles in one record invalidate the whole map instead.
//
// The chain follows the published virtual shadow maps: Unreal Engine's ("Virtual Shadow Maps"
// documentation: cached pages redrawn only when invalidated, a light change invalidating the map) and
// Timberdoodle's (GPU Zen 3, "Virtual Shadow Maps": marking, allocation and drawing driven by the GPU).
//
// Several maps may share one pool texture and one entry buffer (render/virtual_page_storage.h:
// VirtualPageStorageSet::storageFor(i) for map i), so that a lit pass binds those once for up to four
// lights: each map draws into its own square of the texture and updates its own range of the buffer, and
// its lookupData() carries where they are (poolOriginY, firstEntry). Maps sharing storage may record in
// one command list, one after the other.
//
// A steady record allocates nothing: the uniform data of each record goes into one of framesInFlight + 1
// slots of a host-visible buffer the map owns, so record at most once per frame (or per one-off command
// list that the caller waits for).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/device.h"
#include "penumbra/camera.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/virtual_page_draw_pass.h"
#include "render/virtual_page_mark_pass.h"
#include "render/virtual_page_storage.h"
#include "render/virtual_page_table_pass.h"
#include "virtual_page_structs.h"
#include "virtual_shadow_structs.h"

namespace penumbra {

struct VirtualShadowMapConfig {
    VirtualClipmapConfig clipmap;
    uint32_t poolPagesPerSide = 16;  // the pool holds poolPagesPerSide^2 physical pages
    uint32_t keepFrames = 8;         // unrequested pages stay resident this many frames (VirtualPageTablePass)
    ShadowRasterOptions raster;      // render.meshletCulling, shadows.lodErrorTexels for the page drawing
};

class VirtualShadowMap {
public:
    static constexpr uint32_t kMaxInvalidations = 64;  // rectangles per record; more invalidate everything

    // Draws with `raster`, which the atlases may share; `gpuScene` must outlive the map. With `storage`
    // (copied; its texture and buffer must outlive the map: a VirtualPageStorageSet of config's clipmap
    // and poolPagesPerSide), the pool and entries are there; without, the map makes its own.
    VirtualShadowMap(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                     const VirtualShadowMapConfig& config, const VirtualPageStorage* storage = nullptr);
    ~VirtualShadowMap();
    VirtualShadowMap(const VirtualShadowMap&) = delete;
    VirtualShadowMap& operator=(const VirtualShadowMap&) = delete;

    // Records mark -> table update -> draw -> mark drawn for a view whose depth `mainDepth` (a D32
    // texture or the visibility buffer, view.width x view.height, written by earlier passes) is final, a light travelling along
    // wsLightDirection and a scene within wsSceneBounds. marginTexels: the lit pass filter's reach.
    // `invalidations`: the page rectangles of casters that moved since the last record. The levels are
    // picked by the view's pixel footprint times footprintScale (2^lodBias: 0.5 picks texels half as wide
    // as a pixel's footprint); a lit pass must use the same.
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& mainDepth, const CameraView& view,
                const glm::vec3& wsLightDirection, const Aabb& wsSceneBounds, float marginTexels,
                std::span<const gpu_data::VirtualPageInvalidation> invalidations = {}, float footprintScale = 1.0f);
    // The next record invalidates every page (the scene's geometry was replaced, say).
    void invalidateAll() { forceInvalidate_ = true; }

    // What a lit pass samples after the last record (storage buffer, pool texture in General, uniform): the
    // whole buffer and texture, shared or the map's own; lookupData() places this map's entries and pool.
    gpu::BufferHandle pageEntries() const { return table_.entries(); }
    gpu::TextureHandle poolTexture() const { return draw_.poolTexture(); }
    VirtualPageStorage storage() const { return {poolTexture(), draw_.poolOriginY(), pageEntries(), table_.firstEntry()}; }
    const gpu_data::VirtualShadowLookupData& lookupData() const { return lookup_; }
    gpu::BufferSlice lookupDataSlice() const { return lookupSlice_; }  // the last record's copy, in its slot
    uint32_t pageEntryCount() const;  // this map's entries (levelCount * pagesPerSide^2), from storage().firstEntry

    // The last update's VirtualPageStats on the GPU, and its bytes from a readback decoded.
    gpu::BufferSlice stats() const { return table_.stats(); }
    gpu::BufferSlice levelStats() const { return table_.levelStats(); }  // VirtualPageLevelStats
    static gpu_data::VirtualPageStats statsFromReadback(const uint8_t* bytes);

    const VirtualShadowMapConfig& config() const { return config_; }
    const VirtualPageDrawSpace& drawSpace() const { return space_; }
    bool lastRecordInvalidatedAll() const { return lastInvalidatedAll_; }
    // The passes (tests, debugging: VirtualPageTablePass::readState after a record).
    // shadows.virtual.pagesPerFrame (0: as many as the drawing pass's lists hold): the page table's draw
    // budget, never more than the drawing pass draws in a record; the pages past it wait for later frames.
    void setPagesPerFrame(uint32_t pages) { table_.setDrawBudget(virtualDrawBudget(pages, draw_.pagesPerRecord())); }
    uint32_t pagesPerFrame() const { return table_.drawBudget(); }
    VirtualPageTablePass& table() { return table_; }
    VirtualPageDrawPass& draw() { return draw_; }

private:
    // Byte offsets inside one upload slot (256-aligned: any uniform and storage offset alignment).
    struct SlotLayout {
        uint64_t mark = 0, table = 0, lookup = 0, invalidations = 0, size = 0;
    };
    static SlotLayout slotLayout();
    // Whether the light or the bounds differ from the draw space's: then a new space is made.
    bool updateDrawSpace(const glm::vec3& wsLightDirection, const Aabb& wsSceneBounds);

    gpu::Device& device_;
    const GpuScene& scene_;
    VirtualShadowMapConfig config_;
    VirtualPageMarkPass mark_;
    VirtualPageTablePass table_;
    VirtualPageDrawPass draw_;
    VirtualPageDrawSpace space_;
    bool hasSpace_ = false, forceInvalidate_ = false, lastInvalidatedAll_ = false;
    glm::vec3 wsLightDirection_{0.0f};
    Aabb wsSceneBounds_;
    gpu_data::VirtualShadowLookupData lookup_{};
    gpu::BufferSlice lookupSlice_;
    gpu::BufferHandle uploads_;  // slotCount_ slots of slotLayout().size bytes
    uint32_t slotCount_ = 0, nextSlot_ = 0;
};

}  // namespace penumbra
