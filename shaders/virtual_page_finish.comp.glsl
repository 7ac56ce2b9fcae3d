#version 460
// Virtual page table, step 5 of an update (render/virtual_page_table_pass.h), one invocation: takes
// the pages step 4 used off the free list, completes the update's VirtualPageStats, lays out the draw
// list's order (the dirty pages bucket by bucket, coarsest first, up to the draw budget: a frame that
// cannot draw them all draws the pages that finer receivers fall back to first, and the rest stay dirty
// for the next updates) and sizes the indirect dispatches over it.
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
    const uint appended = drawHeader.appended;
    const uint count = min(appended, max(table.drawBudget, 1u));
    uint first = 0u;
    for (uint bucket = bucketCount(); bucket > 0u; --bucket) {
        const uint dirty = counters.levelDrawn[bucket - 1u];
        counters.levelFirst[bucket - 1u] = first;
        counters.levelCursor[bucket - 1u] = 0u;
        counters.levelDrawn[bucket - 1u] = min(dirty, count - min(first, count));
        first += dirty;
    }
    drawHeader.count = count;
    counters.stats.toDraw = count;
    counters.stats.deferred = appended - count;
    drawHeader.pageDispatch = uvec4(count, 1u, 1u, 0u);
    drawHeader.listDispatch = uvec4((appended + kVirtualPageGroupSize - 1u) / kVirtualPageGroupSize, 1u, 1u, 0u);
}
