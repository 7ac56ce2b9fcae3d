#version 460
// Every kStride-th pixel of the main view's depth in x and y, for the tight cascade fit's depth
// reduction in real time (render/visible_surface_pass.h): read back when the frame is done.
#include "pass_bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kSubsampleBindingDepth) uniform sampler2D sceneDepth;
layout(set = kPassSet, binding = kSubsampleBindingDepths, std430) writeonly buffer SubsampleBlock { float depths[]; };
layout(push_constant) uniform SubsampleBlock { SubsampleConstants subsample; };

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= subsample.width || p.y >= subsample.height) return;
    depths[p.y * subsample.width + p.x] = texelFetch(sceneDepth, ivec2(p * subsample.stride), 0).r;
}
