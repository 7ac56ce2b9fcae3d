#version 460
// Virtual page table, step 4 of an update (render/virtual_page_table_pass.h), one invocation per
// missing entry of step 1b (an indirect dispatch the plan sizes): every requested page that is not
// resident takes its place in step 2's order (its level bucket's run, coarsest first) and
// the physical page at that place: the top of the free list, else the candidate of step 3 at that
// place (the least recently requested page not requested this frame, which loses its page), else
// none (overflow, counted by step 5). A new page is dirty and goes on the draw list.
// shadows/virtual_page_pool.h allocate is the CPU rule.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    if (gl_GlobalInvocationID.x >= counters.missing) return;
    const uint entry = missingEntries[gl_GlobalInvocationID.x];
    VirtualPageEntry page = entries[entry];
    const uint bucket = bucketOfEntry(entry);
    const uint order = counters.levelFirst[bucket] + atomicAdd(counters.levelCursor[bucket], 1u);
    const uint freeCount = counters.freeAtAllocation;
    uint physical;
    if (order < freeCount) {
        physical = freePages[freeCount - 1u - order];
    } else if (order - freeCount < counters.evictable) {
        const uint victim = candidates[order - freeCount];  // not requested: no invocation writes it
        physical = entries[victim].physicalPage;
        entries[victim].flags = 0u;
        entries[victim].physicalPage = kVirtualPageNone;
    } else {
        return;  // overflow
    }
    owners[physical] = entry;
    page.physicalPage = physical;
    page.flags = kVirtualPageResident | kVirtualPageDirty | kVirtualPageRequested;
    page.lastRequested = table.frame;
    entries[entry] = page;
    appendDraw(entry, page);
}
