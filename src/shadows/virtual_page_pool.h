#pragma once
// The physical page pool of the virtual shadow maps, as rules on the CPU: which virtual page owns which
// physical page, which pages must be drawn, which are kept. The GPU allocator follows these rules and
// its tests compare against this class; the renderer never reads the GPU's state back.
//
// Each frame the visible receivers request pages (virtual_clipmap.h receiverPages). A requested page
// that is resident is cached: it keeps its physical page and is drawn again only when it is dirty. A
// requested page that is not resident takes a free physical page, or else the least recently
// requested resident page that this frame did not request; it starts dirty. When neither exists the
// request overflows (the caller serves those receivers from a coarser level and reports it): requests
// are served in the order given, so callers list the coarse levels first. A resident page nobody
// requested for more than keepFrames frames is freed (Unreal keeps unrequested pages a few frames).
//
// Dirty pages: newly allocated ones, and those invalidated since they were drawn (a light that
// changed invalidates its maps, a caster that moved the pages its old and new bounds touch).
//
// Clipmaps (virtual_clipmap.h): a page that leaves its level's window gives up its page-table slot to
// the page entering there, so releaseOutside frees it before the frame's update, whether requested or
// not. The GPU page table (render/virtual_page_table_pass.h) follows these rules with one difference
// its tests allow for: among pages requested equally long ago (a tie for least recently requested),
// and among a level's requests when the pool runs out part-way through that level, which ones win
// depends on the order of atomic operations there, and is arbitrary here too.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "shadows/virtual_clipmap.h"

namespace penumbra {

// The shape of a GPU page table (render/virtual_page_table_pass.h): levelCount levels of pagesPerSide^2
// entries. A clipmap's levels (a directional light's) have windows that follow the camera, one level per
// bucket; a table of fixed windows (the mip chains of spot and point light faces, level = mip * faces +
// face: shadows/virtual_faces.h) has none, slot = page, and counts, orders and reports its levels in
// buckets of levelsPerBucket (VirtualPageTableData).
struct VirtualPageTableLayout {
    uint32_t pagesPerSide = 0;
    uint32_t levelCount = 0;
    uint32_t levelsPerBucket = 1;
    bool fixedWindows = false;
    uint32_t entryCount() const { return levelCount * pagesPerSide * pagesPerSide; }
    uint32_t bucketCount() const { return (levelCount + levelsPerBucket - 1) / levelsPerBucket; }
};
VirtualPageTableLayout clipmapTableLayout(const VirtualClipmapConfig& config);

// A virtual page: which map (a directional light's clipmap level, a spot light's mip, a point light's
// face and mip: the caller numbers them) and the page's global coordinates in it.
struct VirtualPageKey {
    uint32_t map = 0;
    glm::ivec2 page{0};
    bool operator==(const VirtualPageKey&) const = default;
};

struct VirtualPageKeyHash {
    size_t operator()(const VirtualPageKey& key) const;
};

// What one frame's update did.
struct VirtualPageFrame {
    uint32_t requested = 0;   // distinct pages requested
    uint32_t cached = 0;      // requested and already resident
    uint32_t allocated = 0;   // requested, not resident, given a physical page
    uint32_t evicted = 0;     // resident pages given to another page or freed after keepFrames
    uint32_t overflowed = 0;  // requested pages that found no physical page
    uint32_t toDraw = 0;      // requested pages that are dirty (allocated or invalidated)
    uint32_t resident = 0;    // resident pages after the update
};

class VirtualPagePool {
public:
    VirtualPagePool(uint32_t capacity, uint32_t keepFrames);

    // Starts a new frame with these requests (duplicates count once). Its `evicted` includes the pages
    // releaseOutside freed since the last update.
    VirtualPageFrame update(std::span<const VirtualPageKey> requests);
    // Frees the resident pages of `map` outside `window` (they left their clipmap level's window, whose
    // slot now belongs to another page); returns how many. Call before the frame's update.
    uint32_t releaseOutside(uint32_t map, const PageRect& window);

    std::optional<uint32_t> physicalPage(const VirtualPageKey& key) const;
    bool resident(const VirtualPageKey& key) const { return pages_.contains(key); }
    // Resident and dirty: its contents must be drawn before it is sampled.
    bool needsDraw(const VirtualPageKey& key) const;
    void markDrawn(const VirtualPageKey& key);

    // Every resident page of `map` becomes dirty (its light changed).
    void invalidateMap(uint32_t map);
    // The resident pages of `map` inside `pages` become dirty (a caster that moved touched them).
    void invalidatePages(uint32_t map, const PageRect& pages);

    uint32_t capacity() const { return capacity_; }
    uint32_t residentCount() const { return uint32_t(pages_.size()); }
    std::vector<VirtualPageKey> residentPages() const;  // in no particular order

private:
    struct Entry {
        uint32_t physical = 0;
        uint64_t lastRequested = 0;  // the frame that last requested it
        bool dirty = true;
    };
    bool allocate(const VirtualPageKey& key, VirtualPageFrame& frame);
    void freeIdlePages(VirtualPageFrame& frame);

    uint32_t capacity_ = 0;
    uint32_t keepFrames_ = 0;
    uint64_t frame_ = 0;
    std::unordered_map<VirtualPageKey, Entry, VirtualPageKeyHash> pages_;
    std::vector<uint32_t> free_;  // physical pages, popped from the back
    uint32_t releasedSinceUpdate_ = 0;  // by releaseOutside, counted in the next update's evicted
};

// Pool pressure: how many steps coarser than its lodBias setting a virtual map marks its pages, from
// the load of its pool in a finished frame (a dynamic resolution, as Unreal Engine's virtual shadow maps
// lower theirs when the page pool fills). A frame that overflowed the pool goes one step coarser (a
// texel twice as wide: about a quarter of the pages), up to kMaxPoolPressureSteps; it goes a step finer
// only when the pages it requested, four times over, would fill at most half the pool, so the choice
// does not flip from frame to frame.
struct VirtualPoolLoad {
    uint32_t requested = 0;   // pages the frame requested
    uint32_t overflowed = 0;  // of those, served by a coarser level for want of a physical page
    uint32_t capacity = 0;    // physical pages of the pool
};
constexpr uint32_t kMaxPoolPressureSteps = 2;
uint32_t nextPoolPressureSteps(uint32_t steps, const VirtualPoolLoad& load);

}  // namespace penumbra
