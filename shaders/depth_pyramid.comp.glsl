#version 460
// One level of the main view's depth pyramid (visibility_structs.h PyramidConstants, cull_structs.h
// CullCamera): each texel keeps the farthest (smallest, reversed Z) depth of the 2 x 2 texels under it,
// clamped at the level's edge; level 0 reads the visibility buffer's depth bits (0 where nothing was
// drawn: the far plane, which hides nothing).
#include "visibility_structs.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = kBindingPyramidVisibility, std430) readonly buffer VisibilityBlock { uvec2 visibility[]; };
layout(set = 0, binding = kBindingPyramid, std430) buffer PyramidBlock { float pyramid[]; };
layout(push_constant) uniform PyramidConstantsBlock { PyramidConstants constants; };

float sourceDepth(uvec2 texel) {
    uint index = texel.y * constants.source.y + texel.x;
    if (constants.source.w != 0u) return uintBitsToFloat(visibility[index].y);  // the word's high half
    return pyramid[constants.source.x + index];
}

void main() {
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(texel, constants.target.yz))) return;
    uvec2 last = constants.source.yz - 1u;
    float farthest = min(min(sourceDepth(min(texel * 2u, last)), sourceDepth(min(texel * 2u + uvec2(1u, 0u), last))),
                         min(sourceDepth(min(texel * 2u + uvec2(0u, 1u), last)), sourceDepth(min(texel * 2u + 1u, last))));
    pyramid[constants.target.x + texel.y * constants.target.y + texel.x] = farthest;
}
