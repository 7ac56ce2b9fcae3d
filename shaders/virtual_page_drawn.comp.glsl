#version 460
// Virtual page table, after the pages of the draw list are drawn (render/virtual_page_table_pass.h
// recordMarkDrawn, an indirect dispatch sized by the finish step): they are no longer dirty.
// shadows/virtual_page_pool.h markDrawn is the CPU rule.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= drawHeader.count) return;
    const uint entry = draws[index].entry;
    entries[entry].flags &= ~kVirtualPageDirty;
}
