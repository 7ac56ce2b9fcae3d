#version 460
// Sizes the indirect dispatches of the compute rasterizers' passes 2 and 3 (and the shadow
// rasterizer's pass 1, over its work items) from their counters.
#include "pass_bindings.h"
#include "cull_structs.h"

layout(local_size_x = 1) in;
layout(set = kPassSet, binding = kRasterBindingCounters, std430) buffer CounterBlock { RasterCounters counters; };
layout(push_constant) uniform ArgsBlock { RasterArgsConstants args; };

uvec4 dispatchFor(uint count) {
    return uvec4(min(count, kRasterDispatchWidth), (count + kRasterDispatchWidth - 1u) / kRasterDispatchWidth, 1u, 0u);
}

void main() {
    if (args.queue == kRasterArgsLarge) counters.largeDispatch = dispatchFor(min(counters.largeQueued, args.largeCapacity));
    else if (args.queue == kRasterArgsWork) counters.workDispatch = dispatchFor(min(counters.workQueued, args.workCapacity));
    else counters.chunkDispatch = dispatchFor(min(counters.chunksQueued, args.chunkCapacity));
}
