#version 460
// Empties the virtual page table (render/virtual_page_table_pass.h): no entry resident, no physical
// page owned, every physical page on the free list (page 0 on top, handed out first, as
// shadows/virtual_page_pool.h does). Recorded once before the first update and after reset().
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i < table.entryCount) entries[i] = VirtualPageEntry(kVirtualPageNone, 0u, 0, 0, 0u, 0.0, 0.0, 0u);
    if (i < table.capacity) {
        owners[i] = kVirtualPageNone;
        freePages[i] = table.capacity - 1u - i;
    }
    if (i == 0u) pool = VirtualPagePoolHeader(table.capacity, table.capacity, 0u, 0u);
}
