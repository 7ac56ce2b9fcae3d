#version 460
// Virtual page table, step 3 of an update (render/virtual_page_table_pass.h), one invocation per
// physical page: lists the eviction
// candidates (resident, not requested this frame) oldest first, each age's run where step 2 placed
// it; within one age the order is that of the atomics. Nothing to do when the free list serves every
// missing page.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint physical = gl_GlobalInvocationID.x;  // one invocation per physical page
    if (physical >= table.capacity || counters.missing <= counters.freeAtAllocation) return;
    const uint entry = owners[physical];
    if (entry == kVirtualPageNone || pageRequested(entry)) return;
    const VirtualPageEntry page = entries[entry];
    if (!isResident(page.flags)) return;
    const uint bucket = ageBucket(page);
    candidates[counters.ageFirst[bucket] + atomicAdd(counters.ageCursor[bucket], 1u)] = entry;
}
