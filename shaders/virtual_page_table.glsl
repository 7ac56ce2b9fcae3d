// The GPU page table and physical page allocator of a directional light's virtual shadow map
// (render/virtual_page_table_pass.h): the buffers every step binds and the slot arithmetic they share.
// Each shader reads a subset of the blocks; render/pass_layouts.cpp declares exactly that subset.
//
// The allocation stays on the GPU with no readback, as in the published virtual shadow maps:
// Timberdoodle's (GPU Zen 3, "Virtual Shadow Maps": a page table per clipmap level addressed
// wrap-around, physical pages handed out from a GPU free list) and Unreal Engine's ("Virtual Shadow
// Maps" documentation: cached pages, unrequested pages kept a few frames). The rules are those of
// shadows/virtual_page_pool.h, the CPU reference the render tests compare with.
#ifndef PENUMBRA_VIRTUAL_PAGE_TABLE_GLSL
#define PENUMBRA_VIRTUAL_PAGE_TABLE_GLSL
#include "pass_bindings.h"
#include "virtual_page_structs.h"

layout(set = kPassSet, binding = kPageTableBindingFrame, std140) uniform PageTableBlock { VirtualPageTableData table; };
layout(set = kPassSet, binding = kPageTableBindingRequests, std430) readonly buffer PageRequestBlock { uint requestWords[]; };
layout(set = kPassSet, binding = kPageTableBindingEntries, std430) buffer PageEntryBlock { VirtualPageEntry entries[]; };
layout(set = kPassSet, binding = kPageTableBindingOwners, std430) buffer PageOwnerBlock { uint owners[]; };
layout(set = kPassSet, binding = kPageTableBindingPool, std430) buffer PagePoolBlock {
    VirtualPagePoolHeader pool;
    uint freePages[];
};
layout(set = kPassSet, binding = kPageTableBindingCounters, std430) buffer PageCounterBlock { VirtualPageCounters counters; };
layout(set = kPassSet, binding = kPageTableBindingCandidates, std430) buffer PageCandidateBlock { uint candidates[]; };
layout(set = kPassSet, binding = kPageTableBindingDrawList, std430) buffer PageDrawBlock {
    VirtualPageDrawHeader drawHeader;
    VirtualPageDraw draws[];
};
layout(set = kPassSet, binding = kPageTableBindingInvalidations, std430) readonly buffer PageInvalidationBlock {
    VirtualPageInvalidation invalidations[];
};
layout(set = kPassSet, binding = kPageTableBindingMissing, std430) buffer PageMissingBlock { uint missingEntries[]; };

uint pagesPerLevel() { return table.pagesPerSide * table.pagesPerSide; }

uint levelOfEntry(uint entry) { return entry / pagesPerLevel(); }

// The bucket the counters, the stats and the allocation order use (VirtualPageTableData).
uint bucketOfEntry(uint entry) { return levelOfEntry(entry) / table.levelsPerBucket; }

uint bucketCount() { return (table.levelCount + table.levelsPerBucket - 1u) / table.levelsPerBucket; }

// The first page of a level's window (the pages [0, pagesPerSide) in a table of fixed windows).
ivec2 windowMinPage(uint level) {
    if (table.fixedWindows != 0u) return ivec2(0);
    return ivec2(table.levels[level].minPageX, table.levels[level].minPageY);
}

// The global page that entry `entry`'s slot holds this frame: the page of its level's window whose
// coordinates are congruent to the slot's modulo pagesPerSide (with fixed windows: the slot itself).
ivec2 windowPageOfEntry(uint entry) {
    const uint n = table.pagesPerSide;
    const uint slot = entry % pagesPerLevel();
    if (table.fixedWindows != 0u) return ivec2(slot % n, slot / n);
    const VirtualPageLevelWindow window = table.levels[levelOfEntry(entry)];
    const uvec2 offset = (uvec2(slot % n, slot / n) + n - uvec2(window.minSlotX, window.minSlotY)) % n;
    return ivec2(window.minPageX, window.minPageY) + ivec2(offset);
}

// The entry of a global page inside its level's window.
uint entryOfWindowPage(uint level, ivec2 page) {
    const uint n = table.pagesPerSide;
    if (table.fixedWindows != 0u) return level * pagesPerLevel() + uint(page.y) * n + uint(page.x);
    const VirtualPageLevelWindow window = table.levels[level];
    const uvec2 slot = (uvec2(page - ivec2(window.minPageX, window.minPageY)) + uvec2(window.minSlotX, window.minSlotY)) % n;
    return level * pagesPerLevel() + slot.y * n + slot.x;
}

bool pageRequested(uint entry) { return ((requestWords[entry / 32u] >> (entry % 32u)) & 1u) != 0u; }

bool isResident(uint flags) { return (flags & kVirtualPageResident) != 0u; }

// Frames since the page was last requested, as an eviction bucket (age - 1; ages run from 1 to
// keepFrames once the idle pages are freed).
uint ageBucket(VirtualPageEntry entry) {
    return min(table.frame - entry.lastRequested, kVirtualPageMaxKeepFrames) - 1u;
}

// Appends a resident, requested, dirty page to the update's draw list, in the unordered half after the
// list itself (step 6 orders it).
void appendDraw(uint entry, VirtualPageEntry page) {
    atomicAdd(counters.levelDrawn[bucketOfEntry(entry)], 1u);
    draws[table.capacity + atomicAdd(drawHeader.appended, 1u)] = VirtualPageDraw(entry, page.physicalPage, page.pageX, page.pageY);
}

#endif
