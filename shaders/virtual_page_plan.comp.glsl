#version 460
// Virtual page table, step 2 of an update (render/virtual_page_table_pass.h), one invocation: the
// order in which step 4 hands out pages. Missing pages are served level bucket by bucket, coarsest
// first (a prefix over the buckets' counts), so that when the pool runs out the fine levels overflow and
// their receivers fall back to a coarser level, never to a hole. Physical pages come from the free
// list first, then from the eviction candidates oldest first (a prefix over the ages, one bucket per
// frame: exact least-recently-requested order up to ties within a frame).
#include "virtual_page_table.glsl"
layout(local_size_x = 1) in;

void main() {
    uint first = 0u;
    for (uint bucket = bucketCount(); bucket > 0u; --bucket) {
        counters.levelFirst[bucket - 1u] = first;
        first += counters.levelMissing[bucket - 1u];
    }
    first = 0u;
    for (uint age = table.keepFrames; age > 0u; --age) {
        counters.ageFirst[age - 1u] = first;
        first += counters.ageCount[age - 1u];
    }
    counters.freeAtAllocation = pool.freeCount;
    counters.allocateDispatch = uvec4((counters.missing + kVirtualPageGroupSize - 1u) / kVirtualPageGroupSize, 1u, 1u, 0u);
}
