#version 460
// Virtual page table, step 1b of an update (render/virtual_page_table_pass.h): one invocation per word
// of the request bits (32 entries). Counts the requested pages (all and per level) and lists those
// that are not resident after step 1 (missing: never held, freed by step 1, or an overflow of an
// earlier frame) for step 4, each level bucket's count in levelMissing for step 2's order.
#include "virtual_page_table.glsl"
layout(local_size_x = kVirtualPageGroupSize) in;

void main() {
    const uint word = gl_GlobalInvocationID.x;
    if (word * 32u >= table.entryCount) return;
    uint bits = requestWords[word];
    if (bits == 0u) return;  // most words
    atomicAdd(counters.stats.requested, uint(bitCount(bits)));
    while (bits != 0u) {
        const uint entry = word * 32u + uint(findLSB(bits));
        bits &= bits - 1u;
        if (entry >= table.entryCount) break;
        const uint bucket = bucketOfEntry(entry);
        atomicAdd(counters.levelRequested[bucket], 1u);
        const VirtualPageEntry page = entries[entry];
        if (isResident(page.flags)) continue;  // cached: step 1 counted it
        const ivec2 windowPage = windowPageOfEntry(entry);
        entries[entry] = VirtualPageEntry(kVirtualPageNone, kVirtualPageRequested, windowPage.x, windowPage.y,
                                          page.lastRequested, 0.0, 0.0, 0u);
        atomicAdd(counters.levelMissing[bucket], 1u);
        missingEntries[atomicAdd(counters.missing, 1u)] = entry;
    }
}
