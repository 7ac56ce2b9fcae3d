// The virtual shadow maps' GPU page table and physical page allocator (render/virtual_page_table_pass.h)
// against its CPU reference (shadows/virtual_page_pool.h), on lavapipe with validation: request bits
// fed directly, frame after frame. Pages are compared as sets of (level, global page): which physical
// page a page gets depends on the order of the GPU's atomics. So does which page of one age is evicted
// and which requests of one level overflow when the pool runs out in that level; the tests that
// compare the sets exactly avoid those ties, and the others check the counts and the invariants.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "render/virtual_page_table_pass.h"
#include "render_test_support.h"
#include "shadows/virtual_page_marking.h"
#include "shadows/virtual_page_pool.h"

namespace penumbra::test {
namespace {

using gpu_data::VirtualPageEntry;
using PageId = std::tuple<uint32_t, int32_t, int32_t>;  // level, global page x, y
using PageSet = std::set<PageId>;

// 8 pages a side, 4 levels; level 0's pages are 1 m wide, level i's 2^i m.
VirtualClipmapConfig smallConfig() { return {.resolution = 64, .pageSize = 8, .levelCount = 4, .firstLevelSize = 8.0f}; }

struct Frame {
    glm::vec2 lsCamera{0.5f};
    std::vector<PageId> requests;  // inside the levels' windows
    bool invalidateAll = false;
    std::vector<std::pair<uint32_t, PageRect>> invalidations;  // (level, pages)
};

Frame requesting(std::vector<PageId> pages, const glm::vec2& lsCamera = glm::vec2(0.5f)) {
    Frame frame;
    frame.lsCamera = lsCamera;
    frame.requests = std::move(pages);
    return frame;
}

PageId idOf(const VirtualPageKey& key) { return {key.map, key.page.x, key.page.y}; }
VirtualPageKey keyOf(const PageId& id) { return {std::get<0>(id), {std::get<1>(id), std::get<2>(id)}}; }

// The CPU reference driven the way the GPU update runs: invalidations, pages leaving their windows,
// then the requests, coarse levels first.
class Reference {
public:
    Reference(const VirtualClipmapConfig& config, uint32_t capacity, uint32_t keepFrames)
        : config_(config), pool_(capacity, keepFrames) {}

    VirtualPageFrame update(const Frame& frame) {
        for (uint32_t level = 0; level < config_.levelCount && frame.invalidateAll; ++level) pool_.invalidateMap(level);
        for (const auto& [level, pages] : frame.invalidations) pool_.invalidatePages(level, pages);
        for (uint32_t level = 0; level < config_.levelCount; ++level)
            pool_.releaseOutside(level, placeClipmapLevel(config_, level, frame.lsCamera).window);
        requests_.clear();
        for (const PageId& id : frame.requests) requests_.push_back(keyOf(id));
        std::stable_sort(requests_.begin(), requests_.end(),
                         [](const VirtualPageKey& a, const VirtualPageKey& b) { return a.map > b.map; });
        return pool_.update(requests_);
    }
    void markDrawn() {
        for (const VirtualPageKey& key : requests_)
            if (pool_.needsDraw(key)) pool_.markDrawn(key);
    }
    PageSet resident() const { return select([](const VirtualPageKey&) { return true; }); }
    PageSet dirty() const { return select([&](const VirtualPageKey& key) { return pool_.needsDraw(key); }); }
    PageSet toDraw() const {
        PageSet pages;
        for (const VirtualPageKey& key : requests_)
            if (pool_.needsDraw(key)) pages.insert(idOf(key));
        return pages;
    }

private:
    template <typename Keep>
    PageSet select(Keep keep) const {
        PageSet pages;
        for (const VirtualPageKey& key : pool_.residentPages())
            if (keep(key)) pages.insert(idOf(key));
        return pages;
    }
    VirtualClipmapConfig config_;
    VirtualPagePool pool_;
    std::vector<VirtualPageKey> requests_;
};

// What the GPU holds after an update, as sets of pages.
struct GpuView {
    VirtualPageTableState state;
    PageSet resident, dirty, toDraw;
    std::vector<uint32_t> physicalOf;     // by entry, kVirtualPageNone when not resident
    std::map<PageId, uint32_t> physical;  // of the resident pages
};

class VirtualPageTableTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }

    static std::vector<uint32_t> requestWords(const VirtualClipmapConfig& config, const Frame& frame) {
        VirtualPageRequests bits(config);
        for (const auto& [level, x, y] : frame.requests) {
            const ClipmapLevel placed = placeClipmapLevel(config, level, frame.lsCamera);
            EXPECT_TRUE(placed.window.contains({{x, y}, {x, y}})) << "the test requests a page outside its window";
            bits.request(level, pageTableSlot(placed, {x, y}));
        }
        return bits.words;
    }

    static GpuView update(VirtualPageTablePass& pass, const VirtualClipmapConfig& config, const Frame& frame) {
        std::vector<gpu_data::VirtualPageInvalidation> rects;
        for (const auto& [level, pages] : frame.invalidations) rects.push_back(virtualPageInvalidation(level, pages));
        pass.updateNow(requestWords(config, frame), frame.lsCamera, frame.invalidateAll, rects);
        GpuView view{pass.readState(), {}, {}, {}, {}, {}};
        const uint32_t perLevel = pagesPerSide(config) * pagesPerSide(config);
        for (uint32_t entry = 0; entry < view.state.entries.size(); ++entry) {
            const VirtualPageEntry& e = view.state.entries[entry];
            const bool resident = e.flags & gpu_data::kVirtualPageResident;
            view.physicalOf.push_back(resident ? e.physicalPage : gpu_data::kVirtualPageNone);
            if (!resident) continue;
            view.resident.insert({entry / perLevel, e.pageX, e.pageY});
            view.physical[{entry / perLevel, e.pageX, e.pageY}] = e.physicalPage;
            if (e.flags & gpu_data::kVirtualPageDirty) view.dirty.insert({entry / perLevel, e.pageX, e.pageY});
        }
        for (const gpu_data::VirtualPageDraw& draw : view.state.draws) view.toDraw.insert({draw.entry / perLevel, draw.pageX, draw.pageY});
        return view;
    }

    // Every physical page is owned by one resident entry or is on the free list, never both or twice;
    // the draw list holds requested resident dirty pages, each once.
    static void expectConsistent(const GpuView& view, uint32_t capacity, const std::string& what) {
        const VirtualPageTableState& s = view.state;
        std::vector<uint32_t> holders(capacity, 0);
        for (uint32_t entry = 0; entry < s.entries.size(); ++entry) {
            const uint32_t physical = view.physicalOf[entry];
            if (physical == gpu_data::kVirtualPageNone) continue;
            ASSERT_LT(physical, capacity) << what;
            ++holders[physical];
            EXPECT_EQ(s.owners[physical], entry) << what << ": owner of physical page " << physical;
        }
        for (uint32_t physical : s.freePages) {
            ASSERT_LT(physical, capacity) << what;
            ++holders[physical];
            EXPECT_EQ(s.owners[physical], gpu_data::kVirtualPageNone) << what << ": free page " << physical << " owned";
        }
        for (uint32_t physical = 0; physical < capacity; ++physical)
            EXPECT_EQ(holders[physical], 1u) << what << ": physical page " << physical << " held by " << holders[physical];
        EXPECT_EQ(s.stats.resident, view.resident.size()) << what;
        EXPECT_EQ(s.draws.size(), view.toDraw.size()) << what << ": a page listed twice";
        EXPECT_EQ(s.drawHeader.pageDispatch.x, s.draws.size()) << what;
        EXPECT_EQ(s.drawHeader.appended, s.draws.size() + s.stats.deferred) << what;
        EXPECT_EQ(s.drawHeader.listDispatch.x, (s.drawHeader.appended + 63) / 64) << what;
        for (const gpu_data::VirtualPageDraw& draw : s.draws) {
            const VirtualPageEntry& e = s.entries[draw.entry];
            EXPECT_EQ(e.flags, gpu_data::kVirtualPageResident | gpu_data::kVirtualPageDirty | gpu_data::kVirtualPageRequested)
                << what << ": entry " << draw.entry << " drawn";
            EXPECT_EQ(draw.physicalPage, e.physicalPage) << what;
        }
    }

    static void expectStats(const gpu_data::VirtualPageStats& gpu, const VirtualPageFrame& cpu, const std::string& what) {
        EXPECT_EQ(gpu.requested, cpu.requested) << what;
        EXPECT_EQ(gpu.cached, cpu.cached) << what;
        EXPECT_EQ(gpu.allocated, cpu.allocated) << what;
        EXPECT_EQ(gpu.evicted, cpu.evicted) << what;
        EXPECT_EQ(gpu.overflowed, cpu.overflowed) << what;
        EXPECT_EQ(gpu.toDraw, cpu.toDraw) << what;
        EXPECT_EQ(gpu.resident, cpu.resident) << what;
    }

    // One frame on both sides, compared exactly; the drawn pages are then marked drawn on both.
    static GpuView expectSameFrame(VirtualPageTablePass& pass, Reference& cpu, const VirtualClipmapConfig& config,
                                   const Frame& frame, const std::string& what) {
        const VirtualPageFrame expected = cpu.update(frame);
        GpuView view = update(pass, config, frame);
        expectConsistent(view, pass.capacity(), what);
        expectStats(view.state.stats, expected, what);
        EXPECT_EQ(view.resident, cpu.resident()) << what << ": resident pages";
        EXPECT_EQ(view.dirty, cpu.dirty()) << what << ": dirty pages";
        EXPECT_EQ(view.toDraw, cpu.toDraw()) << what << ": pages to draw";
        pass.markDrawnNow();
        cpu.markDrawn();
        return view;
    }

    // The GPU table and its CPU reference, one pool each, for smallConfig.
    struct Pools {
        Pools(gpu::Device& device, uint32_t capacity, uint32_t keepFrames)
            : gpu(device, config, capacity, keepFrames), cpu(config, capacity, keepFrames) {}
        // One frame on both, compared exactly, then drawn.
        GpuView frame(const Frame& frame, const std::string& what) { return expectSameFrame(gpu, cpu, config, frame, what); }
        const VirtualClipmapConfig config = smallConfig();
        VirtualPageTablePass gpu;
        Reference cpu;
    };
};

uint32_t nextRandom(uint32_t& state) {
    state = state * 1664525u + 1013904223u;  // a linear congruential generator: the same frames every run
    return state >> 8;
}

// Frames of a camera drifting across pages (windows shift on every level, now and then), each level
// requesting a block of pages around the camera and a few scattered ones, levels going idle for a
// few frames and coming back, and casters invalidating rectangles.
std::vector<Frame> driftingFrames(const VirtualClipmapConfig& config, uint32_t count) {
    std::vector<Frame> frames;
    uint32_t random = 7u;
    glm::vec2 lsCamera(-3.2f, 5.7f);
    for (uint32_t f = 0; f < count; ++f) {
        Frame frame;
        if (f % 5 != 4) lsCamera += glm::vec2(0.45f, -0.3f);  // every fifth frame the camera rests
        frame.lsCamera = lsCamera;
        for (uint32_t level = 0; level < config.levelCount; ++level) {
            if ((f / 3 + level) % 4 == 3) continue;  // this level is idle for a few frames
            const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
            const glm::ivec2 centre = pageOf(placed, lsCamera);
            const int32_t reach = int32_t(1 + (f + level) % 3);
            for (int32_t y = -reach; y <= reach / 2; ++y)
                for (int32_t x = -reach / 2; x <= reach; ++x) frame.requests.push_back({level, centre.x + x, centre.y + y});
            for (uint32_t i = 0; i < 3; ++i) {
                const glm::ivec2 page = placed.window.min + glm::ivec2(nextRandom(random) % placed.pagesPerSide,
                                                                       nextRandom(random) % placed.pagesPerSide);
                frame.requests.push_back({level, page.x, page.y});
            }
            if (nextRandom(random) % 4 == 0) {
                const glm::ivec2 corner = centre + glm::ivec2(int32_t(nextRandom(random) % 5) - 2, int32_t(nextRandom(random) % 5) - 2);
                frame.invalidations.push_back({level, PageRect{corner, corner + glm::ivec2(1, 2)}});
            }
        }
        frame.invalidateAll = f == 17;
        frames.push_back(std::move(frame));
    }
    return frames;
}

TEST_F(VirtualPageTableTest, AFrameSequenceEqualsTheCpuReferenceFrameByFrame) {
    constexpr uint32_t kCapacity = 256, kKeepFrames = 3;  // as many pages as entries: no eviction by pressure
    Pools pools(gpu(), kCapacity, kKeepFrames);
    uint32_t cachedFrames = 0, idleFrees = 0, invalidated = 0;
    const std::vector<Frame> frames = driftingFrames(pools.config, 40);
    for (uint32_t f = 0; f < frames.size(); ++f) {
        const GpuView view = pools.frame(frames[f], "frame " + std::to_string(f));
        cachedFrames += view.state.stats.cached > 0;
        idleFrees += view.state.stats.evicted > 0;
        invalidated += !frames[f].invalidations.empty() && view.state.stats.toDraw > view.state.stats.allocated;
        if (HasFailure()) break;
    }
    // The sequence exercises what it is meant to.
    EXPECT_GT(cachedFrames, 30u);
    EXPECT_GT(idleFrees, 10u);
    EXPECT_GT(invalidated, 3u);
}

TEST_F(VirtualPageTableTest, AnUnrequestedPageSurvivesKeepFramesFramesAndIsFreedAfter) {
    Pools pools(gpu(), 16, 3);
    const Frame requested = requesting({{1, 0, 0}, {0, 2, -1}});
    const Frame idle{};
    const PageSet both = {{1, 0, 0}, {0, 2, -1}};
    EXPECT_EQ(pools.frame(requested, "requested").resident, both);
    for (uint32_t f = 1; f <= 3; ++f) {
        const GpuView view = pools.frame(idle, "idle frame " + std::to_string(f));
        EXPECT_EQ(view.resident, both) << "kept " << f << " of 3 frames";
        EXPECT_EQ(view.state.stats.evicted, 0u);
    }
    const GpuView freed = pools.frame(idle, "idle frame 4");
    EXPECT_TRUE(freed.resident.empty());
    EXPECT_EQ(freed.state.stats.evicted, 2u);
    EXPECT_EQ(freed.state.freePages.size(), 16u);
    // A request in between starts the count again; the page comes back cached, not drawn.
    pools.frame(requested, "requested again");
    pools.frame(idle, "idle 1");
    const GpuView cached = pools.frame(requested, "re-requested");
    EXPECT_EQ(cached.state.stats.cached, 2u);
    EXPECT_EQ(cached.state.stats.toDraw, 0u);
    for (uint32_t f = 1; f <= 3; ++f) EXPECT_EQ(pools.frame(idle, "idle again").resident, both);
    EXPECT_TRUE(pools.frame(idle, "idle 4 again").resident.empty());
}

TEST_F(VirtualPageTableTest, AFullPoolEvictsTheLeastRecentlyRequestedPagesFirst) {
    Pools pools(gpu(), 4, 10);
    for (int32_t x = 0; x < 4; ++x)  // pages 0..3 of level 0, one a frame: four ages
        pools.frame(requesting({{0, x, 0}}), "page " + std::to_string(x));
    const GpuView two = pools.frame(requesting({{0, -1, 1}, {0, -2, 1}}), "two new pages");
    EXPECT_EQ(two.resident, (PageSet{{0, 2, 0}, {0, 3, 0}, {0, -1, 1}, {0, -2, 1}})) << "pages 0 and 1 were the oldest";
    EXPECT_EQ(two.state.stats.evicted, 2u);
    const GpuView one = pools.frame(requesting({{0, 2, 0}, {0, 3, 1}}), "one new page");
    EXPECT_EQ(one.resident, (PageSet{{0, 2, 0}, {0, 3, 1}, {0, -1, 1}, {0, -2, 1}})) << "page 3 was the oldest unrequested";
}

// Pool exhaustion: 10 physical pages for 14 requests over three levels, then new requests while the
// pool is full.
TEST_F(VirtualPageTableTest, AnExhaustedPoolKeepsCoarseLevelsOverflowsFineOnesAndEvictsNothingRequested) {
    Pools pools(gpu(), 10, 5);
    const auto row = [](uint32_t level, int32_t count, int32_t y) {
        std::vector<PageId> pages;
        for (int32_t x = -2; x < count - 2; ++x) pages.push_back({level, x, y});
        return pages;
    };
    const auto levelCounts = [](const PageSet& pages) {
        std::vector<uint32_t> counts(4, 0);
        for (const PageId& id : pages) ++counts[std::get<0>(id)];
        return counts;
    };
    const auto join = [](std::initializer_list<std::vector<PageId>> parts) {
        std::vector<PageId> all;
        for (const std::vector<PageId>& part : parts) all.insert(all.end(), part.begin(), part.end());
        return all;
    };
    // The fine level first in the list: order of the requests does not matter, coarse levels win.
    Frame first = requesting(join({row(1, 6, 0), row(2, 4, 1), row(3, 4, -1)}));
    const VirtualPageFrame expected = pools.cpu.update(first);
    const GpuView full = update(pools.gpu, pools.config, first);
    expectConsistent(full, 10, "full");
    expectStats(full.state.stats, expected, "full");
    EXPECT_EQ(full.state.stats.overflowed, 4u);
    EXPECT_EQ(levelCounts(full.resident), (std::vector<uint32_t>{0, 2, 4, 4}));
    EXPECT_EQ(levelCounts(full.resident), levelCounts(pools.cpu.resident()));
    for (const PageId& id : join({row(2, 4, 1), row(3, 4, -1)})) EXPECT_TRUE(full.resident.contains(id));
    pools.gpu.markDrawnNow();
    pools.cpu.markDrawn();
    // Level 3 again and 6 new level-0 pages: the 6 unrequested pages (one age) are all evicted.
    const GpuView swapped = pools.frame(requesting(join({row(0, 6, 2), row(3, 4, -1)})), "swapped");
    EXPECT_EQ(swapped.state.stats.evicted, 6u);
    for (const PageId& id : row(3, 4, -1))
        EXPECT_EQ(swapped.physical.at(id), full.physical.at(id)) << "a requested page keeps its physical page";
    // Everything resident is requested again, with 3 more: nothing can be evicted, the 3 overflow.
    const GpuView held = pools.frame(requesting(join({row(0, 6, 2), row(3, 4, -1), row(2, 3, 3)})), "held");
    EXPECT_EQ(held.state.stats.overflowed, 3u);
    EXPECT_EQ(held.state.stats.evicted, 0u);
    EXPECT_EQ(held.resident, swapped.resident);
    EXPECT_EQ(held.physicalOf, swapped.physicalOf);
}

// Under pressure (a small pool, a drifting camera) the sets depend on ties, so the invariants are
// checked: pages owned once, no page requested this frame evicted, a level's requests served only
// once every coarser level's are, the counts.
TEST_F(VirtualPageTableTest, UnderPressureNoRequestedPageIsEvictedAndCoarseLevelsAreServedFirst) {
    const VirtualClipmapConfig config = smallConfig();
    constexpr uint32_t kCapacity = 24;
    VirtualPageTablePass pass(gpu(), config, kCapacity, 2);
    GpuView previous;
    uint32_t overflowFrames = 0, evictionFrames = 0;
    const std::vector<Frame> frames = driftingFrames(config, 30);
    for (uint32_t f = 0; f < frames.size(); ++f) {
        const std::string what = "frame " + std::to_string(f);
        const GpuView view = update(pass, config, frames[f]);
        expectConsistent(view, kCapacity, what);
        const PageSet requested(frames[f].requests.begin(), frames[f].requests.end());
        uint32_t allocated = 0, overflowed = 0, finestAllocated = config.levelCount, coarsestOverflowed = 0;
        for (const PageId& id : requested) {
            const uint32_t level = std::get<0>(id);
            if (previous.resident.contains(id)) {
                EXPECT_TRUE(view.resident.contains(id)) << what << ": a requested resident page was evicted";
                EXPECT_EQ(view.physical.at(id), previous.physical.at(id)) << what << ": and lost its physical page";
            } else if (view.resident.contains(id)) {
                ++allocated;
                finestAllocated = std::min(finestAllocated, level);
            } else {
                ++overflowed;
                coarsestOverflowed = std::max(coarsestOverflowed, level);
            }
        }
        EXPECT_EQ(view.state.stats.requested, requested.size()) << what;
        EXPECT_EQ(view.state.stats.allocated, allocated) << what;
        EXPECT_EQ(view.state.stats.overflowed, overflowed) << what;
        if (overflowed > 0 && allocated > 0) {
            EXPECT_GE(finestAllocated, coarsestOverflowed) << what << ": a finer level was served before a coarser one";
        }
        overflowFrames += overflowed > 0;
        evictionFrames += view.state.stats.evicted > 0 && view.state.freePages.empty();
        pass.markDrawnNow();
        previous = view;
    }
    EXPECT_GT(overflowFrames, 5u);
    EXPECT_GT(evictionFrames, 5u);
}

// The camera moves two level-0 pages along x: exactly the 16 pages of the two columns that left the
// window are freed (their slots now map to the columns that entered), the others keep their physical
// pages, and the new columns take the freed slots when requested.
TEST_F(VirtualPageTableTest, TheWindowMovingFreesExactlyTheSlotsWhosePageLeft) {
    Pools pools(gpu(), 64, 10);
    Frame before = requesting({});  // level 0's window: pages -4..3 on both axes
    for (int32_t y = -4; y < 4; ++y)
        for (int32_t x = -4; x < 4; ++x) before.requests.push_back({0, x, y});
    const GpuView all = pools.frame(before, "before");
    ASSERT_EQ(all.resident.size(), 64u);
    const Frame moved = requesting({}, {2.5f, 0.5f});  // pages -2..5 along x; no requests
    const GpuView after = pools.frame(moved, "moved");
    EXPECT_EQ(after.state.stats.evicted, 16u);
    PageSet kept;
    for (const PageId& id : all.resident)
        if (std::get<1>(id) >= -2) kept.insert(id);
    EXPECT_EQ(after.resident, kept);
    for (const PageId& id : kept) EXPECT_EQ(after.physical.at(id), all.physical.at(id));
    Frame entering = requesting({}, moved.lsCamera);
    for (int32_t y = -4; y < 4; ++y)
        for (int32_t x = 4; x < 6; ++x) entering.requests.push_back({0, x, y});
    const GpuView filled = pools.frame(entering, "entering");
    EXPECT_EQ(filled.state.stats.allocated, 16u);
    EXPECT_EQ(filled.resident.size(), 64u);
}

// Invalidation: rectangles (a caster's old and new bounds) and the whole map (the light changed) make
// exactly the resident pages they cover dirty; the requested ones are drawn.
TEST_F(VirtualPageTableTest, InvalidationMarksExactlyTheCoveredPagesDirtyAndDrawsTheRequestedOnes) {
    Pools pools(gpu(), 64, 10);
    Frame frame = requesting({});
    for (uint32_t level = 0; level < 2; ++level)
        for (int32_t y = -2; y < 2; ++y)
            for (int32_t x = -2; x < 2; ++x) frame.requests.push_back({level, x, y});
    EXPECT_EQ(pools.frame(frame, "drawn").toDraw.size(), 32u);
    EXPECT_TRUE(pools.frame(frame, "cached").toDraw.empty());
    Frame moved = frame;
    std::erase(moved.requests, PageId{0, 1, 1});  // resident, not requested: dirty but not drawn
    moved.invalidations = {{0, PageRect{{0, 0}, {1, 1}}},      // old bounds
                           {0, PageRect{{-1, 0}, {0, 0}}},     // new bounds, overlapping
                           {1, PageRect{{-5, -5}, {-2, -2}}},  // partly outside the window
                           {2, PageRect{{0, 0}, {3, 3}}},      // no resident page
                           {1, PageRect{{3, 3}, {2, 2}}}};     // empty
    const GpuView invalidated = pools.frame(moved, "invalidated");
    EXPECT_EQ(invalidated.dirty, (PageSet{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}, {0, -1, 0}, {1, -2, -2}}));
    EXPECT_EQ(invalidated.toDraw, (PageSet{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {1, -2, -2}}));
    Frame relit = frame;
    relit.invalidateAll = true;
    const GpuView all = pools.frame(relit, "light changed");
    EXPECT_EQ(all.dirty, all.resident);
    EXPECT_EQ(all.toDraw.size(), 32u);
}

// A draw budget smaller than the dirty pages (the drawing pass's lists hold fewer pages than the pool):
// the list holds the coarsest levels' pages first, the rest stay resident and dirty (deferred: their
// receivers read a coarser level) and the next updates list them, a budget at a time.
TEST_F(VirtualPageTableTest, ADrawBudgetListsCoarseLevelsFirstAndTheRestInTheNextUpdates) {
    const VirtualClipmapConfig config = smallConfig();
    VirtualPageTablePass pass(gpu(), config, 64, 8);
    pass.setDrawBudget(5);
    EXPECT_EQ(pass.drawBudget(), 5u);
    // Level 3: 2 pages, level 2: 2, level 1: 3, level 0: 4; 11 to draw.
    Frame frame = requesting({{3, 0, 0}, {3, -1, 0}, {2, 0, 0}, {2, 0, -1}, {1, 0, 0}, {1, 1, 0}, {1, -1, -1},
                              {0, 0, 0}, {0, 1, 1}, {0, -1, 0}, {0, -2, -2}});
    const auto levels = [](const GpuView& view) {
        std::multiset<uint32_t, std::greater<>> drawn;
        for (const PageId& id : view.toDraw) drawn.insert(std::get<0>(id));
        return std::vector<uint32_t>(drawn.begin(), drawn.end());
    };
    const GpuView first = update(pass, config, frame);
    expectConsistent(first, pass.capacity(), "first");
    EXPECT_EQ(first.resident.size(), 11u);
    EXPECT_EQ(first.dirty.size(), 11u);
    EXPECT_EQ(levels(first), (std::vector<uint32_t>{3, 3, 2, 2, 1}));
    EXPECT_EQ(first.state.stats.toDraw, 5u);
    EXPECT_EQ(first.state.stats.deferred, 6u);
    pass.markDrawnNow();
    const GpuView second = update(pass, config, frame);
    expectConsistent(second, pass.capacity(), "second");
    EXPECT_EQ(second.dirty.size(), 6u) << "the first list's pages are drawn";
    EXPECT_EQ(levels(second), (std::vector<uint32_t>{1, 1, 0, 0, 0}));
    for (const PageId& id : second.toDraw) EXPECT_FALSE(first.toDraw.contains(id));
    EXPECT_EQ(second.state.stats.deferred, 1u);
    EXPECT_EQ(second.state.stats.cached, 11u);
    pass.markDrawnNow();
    const GpuView third = update(pass, config, frame);
    expectConsistent(third, pass.capacity(), "third");
    EXPECT_EQ(levels(third), (std::vector<uint32_t>{0}));
    EXPECT_EQ(third.state.stats.deferred, 0u);
    pass.markDrawnNow();
    const GpuView rest = update(pass, config, frame);
    EXPECT_TRUE(rest.toDraw.empty());
    EXPECT_TRUE(rest.dirty.empty());
    pass.setDrawBudget(0);
    EXPECT_EQ(pass.drawBudget(), 1u) << "a budget is at least one page";
}

// A table of fixed windows (spot and point faces' mip chains): 3 mips of 8 faces, level = mip * 8 + face,
// 2 pages a side, so more levels than a clipmap's windows hold (24 > kVirtualPageMaxLevels). Slot = page;
// counts, stats and the allocation order go by bucket (the mip), coarsest first.
constexpr VirtualPageTableLayout kFixedLayout{.pagesPerSide = 2, .levelCount = 24, .levelsPerBucket = 8, .fixedWindows = true};

std::vector<uint32_t> fixedRequestWords(const std::vector<PageId>& requests) {
    std::vector<uint32_t> words((kFixedLayout.entryCount() + 31) / 32, 0u);
    for (const auto& [level, x, y] : requests) {
        const uint32_t bit = gpu_data::virtualPageBit(level, kFixedLayout.pagesPerSide, uint32_t(x), uint32_t(y));
        words[bit / 32] |= 1u << (bit % 32);
    }
    return words;
}

// Random pages of random levels, a rectangle invalidated now and then; levels of a bucket go idle together.
std::vector<Frame> fixedFrames(uint32_t count) {
    std::vector<Frame> frames;
    uint32_t random = 11u;
    for (uint32_t f = 0; f < count; ++f) {
        Frame frame;
        for (uint32_t level = 0; level < kFixedLayout.levelCount; ++level) {
            if ((f / 4 + level / kFixedLayout.levelsPerBucket) % 3 == 2 || nextRandom(random) % 3 == 0) continue;
            for (uint32_t i = nextRandom(random) % 4; i > 0; --i)
                frame.requests.push_back({level, int32_t(nextRandom(random) % 2), int32_t(nextRandom(random) % 2)});
            if (nextRandom(random) % 8 == 0) frame.invalidations.push_back({level, PageRect{{0, 0}, {0, 1}}});
        }
        frame.invalidateAll = f == 9;
        frames.push_back(std::move(frame));
    }
    return frames;
}

TEST_F(VirtualPageTableTest, ATableOfFixedWindowsEqualsTheCpuReferenceBucketByBucket) {
    constexpr uint32_t kCapacity = 96, kKeepFrames = 2;  // every entry fits: no eviction by pressure
    VirtualPageTablePass pass(gpu(), kFixedLayout, kCapacity, kKeepFrames);
    VirtualPagePool cpu(kCapacity, kKeepFrames);
    uint32_t cachedFrames = 0, idleFrees = 0, invalidated = 0;
    const std::vector<Frame> frames = fixedFrames(30);
    for (uint32_t f = 0; f < frames.size(); ++f) {
        const std::string what = "frame " + std::to_string(f);
        const Frame& frame = frames[f];
        for (uint32_t level = 0; level < kFixedLayout.levelCount && frame.invalidateAll; ++level) cpu.invalidateMap(level);
        for (const auto& [level, pages] : frame.invalidations) cpu.invalidatePages(level, pages);
        std::vector<VirtualPageKey> requests;
        for (const PageId& id : frame.requests) requests.push_back(keyOf(id));
        std::stable_sort(requests.begin(), requests.end(), [](const VirtualPageKey& a, const VirtualPageKey& b) {
            return a.map / kFixedLayout.levelsPerBucket > b.map / kFixedLayout.levelsPerBucket;
        });
        const VirtualPageFrame expected = cpu.update(requests);
        std::vector<gpu_data::VirtualPageInvalidation> rects;
        for (const auto& [level, pages] : frame.invalidations) rects.push_back(virtualPageInvalidation(level, pages));
        pass.updateNow(fixedRequestWords(frame.requests), glm::vec2(0.0f), frame.invalidateAll, rects);
        GpuView view{pass.readState(), {}, {}, {}, {}, {}};
        for (uint32_t entry = 0; entry < view.state.entries.size(); ++entry) {
            const VirtualPageEntry& e = view.state.entries[entry];
            const bool resident = e.flags & gpu_data::kVirtualPageResident;
            view.physicalOf.push_back(resident ? e.physicalPage : gpu_data::kVirtualPageNone);
            if (!resident) continue;
            const PageId id{entry / 4, e.pageX, e.pageY};
            EXPECT_EQ(entry % 4, uint32_t(e.pageY * 2 + e.pageX)) << what << ": slot = page";
            view.resident.insert(id);
            if (e.flags & gpu_data::kVirtualPageDirty) view.dirty.insert(id);
        }
        for (const gpu_data::VirtualPageDraw& draw : view.state.draws) view.toDraw.insert({draw.entry / 4, draw.pageX, draw.pageY});
        expectConsistent(view, kCapacity, what);
        expectStats(view.state.stats, expected, what);
        PageSet resident, toDraw;
        for (const VirtualPageKey& key : cpu.residentPages()) resident.insert(idOf(key));
        for (const VirtualPageKey& key : requests)
            if (cpu.needsDraw(key)) toDraw.insert(idOf(key));
        EXPECT_EQ(view.resident, resident) << what;
        EXPECT_EQ(view.toDraw, toDraw) << what;
        // The per-bucket counts of the page view.
        const gpu::BufferSlice levelStats = pass.levelStats();
        gpu_data::VirtualPageLevelStats stats{};
        std::memcpy(&stats, gpu().readBuffer(levelStats.buffer).data() + levelStats.offset, sizeof(stats));
        for (uint32_t bucket = 0; bucket < kFixedLayout.bucketCount(); ++bucket) {
            uint32_t requestedInBucket = 0;
            for (const PageId& id : PageSet(frame.requests.begin(), frame.requests.end()))
                requestedInBucket += std::get<0>(id) / kFixedLayout.levelsPerBucket == bucket;
            EXPECT_EQ(stats.requested[bucket], requestedInBucket) << what << ", bucket " << bucket;
        }
        pass.markDrawnNow();
        for (const VirtualPageKey& key : requests)
            if (cpu.needsDraw(key)) cpu.markDrawn(key);
        cachedFrames += view.state.stats.cached > 0;
        idleFrees += view.state.stats.evicted > 0;
        invalidated += !frame.invalidations.empty() && view.state.stats.toDraw > view.state.stats.allocated;
        if (HasFailure()) break;
    }
    EXPECT_GT(cachedFrames, 20u);
    EXPECT_GT(idleFrees, 5u);
    EXPECT_GT(invalidated, 2u);
}

// When the pool runs out, the coarsest bucket (every face's coarsest mip) is served first.
TEST_F(VirtualPageTableTest, AnExhaustedTableOfFixedWindowsServesTheCoarsestMipOfEveryFaceFirst) {
    VirtualPageTablePass pass(gpu(), kFixedLayout, 40, 2);
    std::vector<PageId> all;
    for (uint32_t level = 0; level < kFixedLayout.levelCount; ++level)
        for (int32_t y = 0; y < 2; ++y)
            for (int32_t x = 0; x < 2; ++x) all.push_back({level, x, y});
    pass.updateNow(fixedRequestWords(all), glm::vec2(0.0f));
    const VirtualPageTableState state = pass.readState();
    EXPECT_EQ(state.stats.allocated, 40u);
    EXPECT_EQ(state.stats.overflowed, 56u);
    uint32_t perBucket[3] = {};
    for (uint32_t entry = 0; entry < state.entries.size(); ++entry)
        if (state.entries[entry].flags & gpu_data::kVirtualPageResident) ++perBucket[entry / 4 / kFixedLayout.levelsPerBucket];
    EXPECT_EQ(perBucket[2], 32u) << "every page of the coarsest mip of the 8 faces";
    EXPECT_EQ(perBucket[1], 8u);
    EXPECT_EQ(perBucket[0], 0u);
}

// The declarations leave no hazard: updates, draws marked, a reset, on a device with synchronization
// validation.
TEST_F(VirtualPageTableTest, UpdatesPassSynchronizationValidation) {
    DeviceOptions options = testDeviceOptions();
    options.synchronizationValidation = true;
    Device syncDevice(options);
    const VirtualClipmapConfig config = smallConfig();
    {
        VirtualPageTablePass pass(gpu::backend(syncDevice), config, 24, 2);
        uint32_t f = 0;
        for (const Frame& frame : driftingFrames(config, 6)) {
            if (++f == 4) pass.reset();
            const GpuView view = update(pass, config, frame);
            expectConsistent(view, 24, "frame " + std::to_string(f));
            pass.markDrawnNow();
        }
    }
    gpu::backend(syncDevice).waitIdle();
    EXPECT_EQ(syncDevice.validationMessageCount(), 0u) << (syncDevice.validationMessageCount() ? syncDevice.validationMessages()[0] : "");
}

}  // namespace
}  // namespace penumbra::test
