#version 460
// Virtual page table, step 5 of an update (render/virtual_page_table_pass.h), one invocation: takes
// the pages step 4 used off the free list, completes the update's VirtualPageStats and sizes the
// indirect dispatches over the draw list.
#include "virtual_page_table.glsl"
layout(local_size_x = 1) in;

void main() {
    const uint missing = counters.missing;
    const uint freeCount = counters.freeAtAllocation;
    const uint allocated = min(missing, freeCount + counters.evictable);
    const uint fromFreeList = min(allocated, freeCount);
    pool.freeCount = freeCount - fromFreeList;
    counters.stats.allocated = allocated;
    counters.stats.overflowed = missing - allocated;
    counters.stats.evicted += allocated - fromFreeList;
    counters.stats.resident = table.capacity - pool.freeCount;
    const uint count = drawHeader.count;
    counters.stats.toDraw = count;
    drawHeader.pageDispatch = uvec4(count, 1u, 1u, 0u);
    drawHeader.listDispatch = uvec4((count + kVirtualPageGroupSize - 1u) / kVirtualPageGroupSize, 1u, 1u, 0u);
}
