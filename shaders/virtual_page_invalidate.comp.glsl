#version 460
// Virtual page table, invalidation by rectangle (render/virtual_page_table_pass.h): one workgroup per
// VirtualPageInvalidation (a caster's old or new bounds on one level, from the CPU) marks dirty every
// resident page of that level inside it and inside the level's window this frame; pages outside the
// window are freed by the update that follows. shadows/virtual_page_pool.h invalidatePages is the
// CPU rule. Before the update, so that the update lists the requested ones to draw.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint index = gl_WorkGroupID.x;
    if (index >= table.invalidationCount) return;
    const VirtualPageInvalidation rect = invalidations[index];
    if (rect.level >= table.levelCount) return;
    const ivec2 windowMin = windowMinPage(rect.level);
    const ivec2 lo = max(ivec2(rect.minPageX, rect.minPageY), windowMin);
    const ivec2 hi = min(ivec2(rect.maxPageX, rect.maxPageY), windowMin + int(table.pagesPerSide) - 1);
    if (any(lessThan(hi, lo))) return;
    const uint width = uint(hi.x - lo.x + 1);
    const uint count = width * uint(hi.y - lo.y + 1);
    for (uint i = gl_LocalInvocationID.x; i < count; i += kVirtualPageGroupSize) {
        const ivec2 page = lo + ivec2(i % width, i / width);
        const uint entry = entryOfWindowPage(rect.level, page);
        const VirtualPageEntry held = entries[entry];
        if (isResident(held.flags) && held.pageX == page.x && held.pageY == page.y)
            atomicOr(entries[entry].flags, kVirtualPageDirty);  // rectangles may overlap
    }
}
