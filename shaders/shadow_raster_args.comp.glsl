#version 460
// Sizes the indirect dispatches of the compute rasterizer's passes 2 and 3 from its counters.
#include "cull_structs.h"

layout(local_size_x = 1) in;
layout(set = 0, binding = 9, std430) buffer CounterBlock { RasterCounters counters; };
layout(push_constant) uniform ArgsConstants { uvec4 which; } args;  // x = 0: large-triangle pass, 1: chunk pass

uvec4 dispatchFor(uint count) {
    return uvec4(min(count, kRasterDispatchWidth), (count + kRasterDispatchWidth - 1u) / kRasterDispatchWidth, 1u, 0u);
}

void main() {
    if (args.which.x == 0u) counters.largeDispatch = dispatchFor(min(counters.counts.x, kRasterMaxLarge));
    else counters.chunkDispatch = dispatchFor(min(counters.counts.y, kRasterMaxChunks));
}
