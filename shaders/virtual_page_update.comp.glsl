#version 460
// Virtual page table, step 1 of an update (render/virtual_page_table_pass.h): one invocation per entry
// (level, wrap-around slot) against this frame's request bits and windows.
// - A resident page that left its level's window (the slot now maps to another page) or that nobody
//   requested for more than keepFrames frames is freed: its physical page goes on the free list.
// - A resident page requested again is cached: lastRequested is refreshed, and it is drawn if dirty.
// - A resident page not requested is an eviction candidate, counted by age.
// - A requested page that is not resident is counted as missing in its level.
// shadows/virtual_page_pool.h (releaseOutside, then update's freeing and caching) is the CPU rule.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void freePhysicalPage(uint physical) {
    owners[physical] = kVirtualPageNone;
    freePages[atomicAdd(pool.freeCount, 1u)] = physical;
    atomicAdd(counters.stats.evicted, 1u);
}

void main() {
    const uint entry = gl_GlobalInvocationID.x;
    if (entry >= table.entryCount) return;
    VirtualPageEntry page = entries[entry];
    const bool requested = pageRequested(entry);
    if (!requested && page.flags == 0u) return;  // empty and not wanted: most entries
    const ivec2 windowPage = windowPageOfEntry(entry);
    bool resident = isResident(page.flags);
    const bool leftWindow = page.pageX != windowPage.x || page.pageY != windowPage.y;
    const bool idle = !requested && table.frame - page.lastRequested > table.keepFrames;
    if (resident && (leftWindow || idle)) {
        freePhysicalPage(page.physicalPage);
        resident = false;
    }
    if (requested) atomicAdd(counters.stats.requested, 1u);
    if (!resident) {
        page = VirtualPageEntry(kVirtualPageNone, requested ? kVirtualPageRequested : 0u, windowPage.x, windowPage.y,
                                page.lastRequested, 0u, 0u, 0u);
        if (requested) {
            atomicAdd(counters.levelMissing[entry / pagesPerLevel()], 1u);
            atomicAdd(counters.missing, 1u);
        }
        entries[entry] = page;
        return;
    }
    page.flags &= kVirtualPageResident | kVirtualPageDirty;
    if (table.invalidateAll != 0u) page.flags |= kVirtualPageDirty;  // the light changed
    if (requested) {
        page.flags |= kVirtualPageRequested;
        page.lastRequested = table.frame;
        atomicAdd(counters.stats.cached, 1u);
        if ((page.flags & kVirtualPageDirty) != 0u) appendDraw(entry, page);
    } else {
        atomicAdd(counters.ageCount[ageBucket(page)], 1u);
        atomicAdd(counters.evictable, 1u);
    }
    entries[entry] = page;
}
