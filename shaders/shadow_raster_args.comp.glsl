#version 460
// Sizes the indirect dispatches of the compute rasterizer's passes 2 and 3 from its counters.
#include "cull_structs.h"

layout(local_size_x = 1) in;
layout(set = 0, binding = 9, std430) buffer CounterBlock { RasterCounters counters; };
layout(push_constant) uniform ArgsConstants {
    uvec4 which;     // x = 0: the large-piece pass, 1: the chunk pass
    uvec4 capacity;  // as shadow_raster.glsl
} args;

uvec4 dispatchFor(uint count) {
    return uvec4(min(count, kRasterDispatchWidth), (count + kRasterDispatchWidth - 1u) / kRasterDispatchWidth, 1u, 0u);
}

void main() {
    if (args.which.x == 0u) counters.largeDispatch = dispatchFor(min(counters.counts.x, args.capacity.x));
    else counters.chunkDispatch = dispatchFor(min(counters.counts.y, args.capacity.y));
}
