#version 460
// Copies a rect of the compute rasterizer's depth buffer (float bits, its atomic-min target) into the
// atlas's R32F image that the lit pass samples: one thread per texel. A compute pass, where a copy into a
// depth image would go through the graphics pipeline's few units (0.74 ms for a 4096² atlas on an H100).
#include "pass_bindings.h"
#include "cull_structs.h"

layout(local_size_x = kAtlasCopyGroupX, local_size_y = kAtlasCopyGroupY) in;

layout(set = kPassSet, binding = kAtlasCopyBindingDepth, std430) readonly buffer DepthBlock { uint depthBits[]; };
layout(set = kPassSet, binding = kAtlasCopyBindingAtlas, r32f) uniform writeonly image2D atlas;
layout(push_constant) uniform AtlasCopyBlock { AtlasCopyConstants constants; };

void main() {
    if (gl_GlobalInvocationID.x >= constants.width || gl_GlobalInvocationID.y >= constants.height) return;
    uvec2 texel = uvec2(constants.originX, constants.originY) + gl_GlobalInvocationID.xy;
    imageStore(atlas, ivec2(texel), vec4(uintBitsToFloat(depthBits[texel.y * constants.depthSide + texel.x])));
}
