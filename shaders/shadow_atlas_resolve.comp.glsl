#version 460
// Copies a rect of the hardware rasterizer's depth target (D32) into the atlas's R32F image that the lit
// pass samples: one thread per texel.
#include "pass_bindings.h"
#include "cull_structs.h"

layout(local_size_x = kAtlasCopyGroupX, local_size_y = kAtlasCopyGroupY) in;

layout(set = kPassSet, binding = kAtlasCopyBindingSource) uniform sampler2D source;
layout(set = kPassSet, binding = kAtlasCopyBindingAtlas, r32f) uniform writeonly image2D atlas;
layout(push_constant) uniform AtlasCopyBlock { AtlasCopyConstants constants; };

void main() {
    if (gl_GlobalInvocationID.x >= constants.width || gl_GlobalInvocationID.y >= constants.height) return;
    ivec2 texel = ivec2(uvec2(constants.originX, constants.originY) + gl_GlobalInvocationID.xy);
    imageStore(atlas, texel, vec4(texelFetch(source, texel, 0).r));
}
