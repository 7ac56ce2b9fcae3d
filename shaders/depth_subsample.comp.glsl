#version 460
// Every kStride-th pixel of the main view's depth in x and y, for the tight cascade fit's depth
// reduction in real time (render/visible_surface_pass.h): read back when the frame is done.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D sceneDepth;
layout(set = 0, binding = 1, std430) writeonly buffer SubsampleBlock { float depths[]; };
layout(push_constant) uniform SubsampleConstants { uvec4 size; } subsample;  // x, y = output size, z = stride

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= subsample.size.x || p.y >= subsample.size.y) return;
    depths[p.y * subsample.size.x + p.x] = texelFetch(sceneDepth, ivec2(p * subsample.size.z), 0).r;
}
