#version 460
// Virtual page table, step 6 of an update (render/virtual_page_table_pass.h), one invocation per
// appended dirty page (an indirect dispatch step 5 sized): each takes the next place of its level
// bucket's run in step 5's order, coarsest bucket first; the places past the draw budget are not on
// the list, so those pages stay dirty and the next update appends them again. Within a bucket the
// order is the atomics'.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= drawHeader.appended) return;
    const VirtualPageDraw draw = draws[table.capacity + index];
    const uint bucket = bucketOfEntry(draw.entry);
    const uint place = counters.levelFirst[bucket] + atomicAdd(counters.levelCursor[bucket], 1u);
    if (place < drawHeader.count) draws[place] = draw;
}
