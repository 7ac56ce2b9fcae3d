#pragma once
// The page table and physical page allocator of one directional light's virtual shadow map, on the
// GPU with no readback on the frame path (shaders/virtual_page_*.comp, virtual_page_table.glsl; the
// layouts are shaders/shared/virtual_page_structs.h). shadows/virtual_page_pool.h holds the rules and
// is the CPU reference the render tests compare with.
//
// One update per frame, after the marking pass (render/virtual_page_mark_pass.h) wrote the request
// bits: invalidation (the rectangles of casters that moved), then the update proper: pages that left
// their level's window or stayed unrequested for more than keepFrames frames are freed; requested
// resident pages are cached; requested missing pages take a free physical page, else the least
// recently requested page not requested this frame, coarse levels before fine ones, else overflow
// (their receivers sample a coarser level: VirtualPageStats::overflowed is the warning's count). The
// requested dirty pages (new, or invalidated) make the draw list, coarse levels first and at most the
// draw budget of them (what the drawing pass draws in a record: the rest stay dirty for the next frames), with its
// indirect dispatch sizes;
// once a later pass has drawn them, recordMarkDrawn clears their dirty flags. An update's work follows
// the pool and the requests, not the levels' slots: the resident pages are visited through their
// owners, the request bits a word at a time (the missing pages listed for the allocation, an indirect
// dispatch), so a still camera's update touches the resident and requested pages only.
//
// GPU-only allocation and wrap-around page tables follow Timberdoodle's virtual shadow maps (GPU Zen
// 3, "Virtual Shadow Maps"); the cache and keep-alive of unrequested pages follow Unreal Engine's
// ("Virtual Shadow Maps" documentation).
//
// Eviction order: candidates are bucketed by age in frames (1 to keepFrames once idle pages are
// freed), so the order is exactly least recently requested at the granularity of frames; between
// pages of the same age, and between a level's requests when the pool runs out part-way through that
// level, atomics decide (the CPU reference's choice there is arbitrary too).
//
// The entries may live in a buffer that several maps share (render/virtual_page_storage.h): then every
// descriptor binds this table's range only (entriesSlice()), so the reset, the update and the rest
// read and write no other map's entries; the owners, free list, counters and draw list stay its own.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/device.h"
#include "render/virtual_page_storage.h"
#include "shadows/virtual_clipmap.h"
#include "shadows/virtual_page_pool.h"
#include "virtual_page_structs.h"

namespace penumbra {

// The uniform data of update number `frame`: each level's window around lsCamera (the light-space
// clipmap centre, lsClipmapCentre) and the pool's rules.
gpu_data::VirtualPageTableData packVirtualPageTable(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                                                    uint32_t frame, uint32_t capacity, uint32_t keepFrames);
// The pages of `level` inside `pages` (a caster's old or new bounds: pagesTouchedByBounds) to redraw.
gpu_data::VirtualPageInvalidation virtualPageInvalidation(uint32_t level, const PageRect& pages);

struct VirtualPageTableInputs {
    gpu::BufferSlice requestWords;   // the marking pass's request bits (VirtualPageMarkPass::requestWords)
    gpu::BufferSlice tableData;      // a VirtualPageTableData from packFrame (uniform; the frame's upload ring)
    gpu::BufferSlice invalidations;  // invalidationCount VirtualPageInvalidations (storage, host-written)
    uint32_t invalidationCount = 0;  // as packed into tableData
};

// A copy of the table's GPU state (tests, debugging).
struct VirtualPageTableState {
    std::vector<gpu_data::VirtualPageEntry> entries;  // by entry: level, then slot y * pagesPerSide + x
    std::vector<uint32_t> owners;                     // by physical page: its entry or kVirtualPageNone
    std::vector<uint32_t> freePages;                  // the free list, bottom first
    gpu_data::VirtualPageStats stats{};               // of the last update
    gpu_data::VirtualPageDrawHeader drawHeader{};
    std::vector<gpu_data::VirtualPageDraw> draws;     // the last update's draw list
};

class VirtualPageTablePass {
public:
    // A table for clipmaps of `config` (at most kVirtualPageMaxLevels levels) and a pool of `capacity`
    // physical pages (1 to 65535: one workgroup per page to draw) that keeps unrequested pages
    // keepFrames frames (at most kVirtualPageMaxKeepFrames). Throws Error for other values. With `shared`
    // whose entries are set, the entries are its records from firstEntry on (firstEntry * 32 bytes a
    // multiple of kVirtualPageEntryAlignment, the buffer long enough: else Error), which the table neither
    // creates nor destroys; without, a buffer of its own.
    VirtualPageTablePass(gpu::Device& device, const VirtualClipmapConfig& config, uint32_t capacity, uint32_t keepFrames,
                         const VirtualPageStorage* shared = nullptr);
    // A table of fixed windows (layout.fixedWindows; at most kVirtualPageMaxLevels buckets), with its own
    // entries; packFrame's lsCamera is then ignored.
    VirtualPageTablePass(gpu::Device& device, const VirtualPageTableLayout& layout, uint32_t capacity, uint32_t keepFrames);
    ~VirtualPageTablePass();
    VirtualPageTablePass(const VirtualPageTablePass&) = delete;
    VirtualPageTablePass& operator=(const VirtualPageTablePass&) = delete;

    // The next update's uniform data; its frame number is one more than the last one packed. Pass
    // invalidateAll when the light changed (every resident page becomes dirty).
    gpu_data::VirtualPageTableData packFrame(const glm::vec2& lsCamera, bool invalidateAll, uint32_t invalidationCount);
    // Records one update (inside a frame or any command list); allocates nothing.
    void record(gpu::CommandList& commands, const VirtualPageTableInputs& inputs);
    // After the pass that drew the last update's draw list: those pages are no longer dirty.
    void recordMarkDrawn(gpu::CommandList& commands);
    // The most pages one update puts on its draw list (clamped to 1..capacity; capacity when never set):
    // what the drawing pass can draw in one record (VirtualPageDrawPass::pagesPerRecord). The dirty pages
    // past it, the finest first, stay dirty for the next updates (VirtualPageStats::deferred); until drawn
    // their receivers sample a coarser level.
    void setDrawBudget(uint32_t pages);
    uint32_t drawBudget() const { return drawBudget_; }
    // The next record starts from an empty table (every page freed).
    void reset() { needsReset_ = true; }

    gpu::BufferHandle entries() const { return entries_; }  // the whole buffer (shared or its own)
    gpu::BufferSlice entriesSlice() const { return {entries_, entriesOffset_, entryBytes()}; }  // this table's range
    uint32_t firstEntry() const { return uint32_t(entriesOffset_ / sizeof(gpu_data::VirtualPageEntry)); }
    uint32_t entryCount() const { return entryCount_; }
    gpu::BufferHandle drawList() const { return drawList_; }  // VirtualPageDrawHeader + VirtualPageDraw[2 * capacity]
    gpu::BufferSlice stats() const;                           // VirtualPageStats of the last update
    gpu::BufferSlice levelStats() const;                      // VirtualPageLevelStats of the last update
    uint32_t capacity() const { return capacity_; }

    // Tests and debugging (each waits for the GPU): one update from request bits (VirtualPageRequests::
    // words), the dirty flags of its draw list cleared, and the whole state read back.
    void updateNow(std::span<const uint32_t> requestWords, const glm::vec2& lsCamera, bool invalidateAll = false,
                   std::span<const gpu_data::VirtualPageInvalidation> invalidations = {});
    void markDrawnNow();
    VirtualPageTableState readState();

private:
    void create(const VirtualPageStorage* shared);
    enum Step : uint32_t { Reset, Invalidate, Update, Requests, Plan, Candidates, Allocate, Finish, Order, Drawn, StepCount };
    void useSharedEntries(const VirtualPageStorage& shared);
    void createBuffers();
    uint64_t entryBytes() const { return uint64_t(entryCount_) * sizeof(gpu_data::VirtualPageEntry); }
    void release();
    void bindStep(gpu::CommandList& commands, Step step);
    void dispatch(gpu::CommandList& commands, Step step, uint32_t groups);
    void ensureTestBuffers(size_t requestBytes, size_t invalidationCount);

    gpu::Device& device_;
    VirtualClipmapConfig config_;   // a clipmap's (layout_.fixedWindows false)
    VirtualPageTableLayout layout_;
    uint32_t capacity_ = 0, keepFrames_ = 0, entryCount_ = 0, drawBudget_ = 0;
    uint32_t frame_ = 0;  // the last update packed
    bool needsReset_ = true;
    bool ownsEntries_ = true;
    uint64_t entriesOffset_ = 0;  // bytes: this table's first entry in entries_
    std::array<gpu::PipelineHandle, StepCount> pipelines_{};
    gpu::BufferHandle entries_, owners_, pool_, counters_, candidates_, drawList_, missing_;
    std::array<gpu::DescriptorWrite, 10> writes_{};  // the record's, kept: no allocation per frame
    // updateNow's host-written inputs.
    gpu::BufferHandle testRequests_, testTable_, testInvalidations_;
    size_t testRequestBytes_ = 0, testInvalidationCapacity_ = 0;
};

}  // namespace penumbra
