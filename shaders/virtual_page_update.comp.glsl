#version 460
// Virtual page table, step 1 of an update (render/virtual_page_table_pass.h): one invocation per
// physical page, for the entry that holds it (owners), against this frame's request bits and windows.
// The work follows the pool's size, not the levels' slots.
// - A resident page that left its level's window (the slot now maps to another page) or that nobody
//   requested for more than keepFrames frames is freed: its physical page goes on the free list.
// - A resident page requested again is cached: lastRequested is refreshed, and it is drawn if dirty.
// - A resident page not requested is an eviction candidate, counted by age.
// Step 1b (virtual_page_requests.comp) then lists the requested pages that are not resident.
// shadows/virtual_page_pool.h (releaseOutside, then update's freeing and caching) is the CPU rule.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint physical = gl_GlobalInvocationID.x;
    if (physical >= table.capacity) return;
    const uint entry = owners[physical];
    if (entry == kVirtualPageNone) return;  // a free page
    VirtualPageEntry page = entries[entry];
    const bool requested = pageRequested(entry);
    const ivec2 windowPage = windowPageOfEntry(entry);
    const bool leftWindow = page.pageX != windowPage.x || page.pageY != windowPage.y;
    const bool idle = !requested && table.frame - page.lastRequested > table.keepFrames;
    if (leftWindow || idle) {
        owners[physical] = kVirtualPageNone;
        freePages[atomicAdd(pool.freeCount, 1u)] = physical;
        atomicAdd(counters.stats.evicted, 1u);
        entries[entry] = VirtualPageEntry(kVirtualPageNone, 0u, windowPage.x, windowPage.y, page.lastRequested, 0.0, 0.0, 0u);
        return;  // requested again, step 1b lists it as missing
    }
    page.flags &= kVirtualPageResident | kVirtualPageDirty;
    if (table.invalidateAll != 0u) page.flags |= kVirtualPageDirty;  // the light changed
    if (requested) {
        page.flags |= kVirtualPageRequested;
        page.lastRequested = table.frame;
        atomicAdd(counters.stats.cached, 1u);
        atomicAdd(counters.levelCached[bucketOfEntry(entry)], 1u);
        if ((page.flags & kVirtualPageDirty) != 0u) appendDraw(entry, page);
    } else {
        atomicAdd(counters.ageCount[ageBucket(page)], 1u);
        atomicAdd(counters.evictable, 1u);
    }
    entries[entry] = page;
}
