#version 460
// One level of the main view's depth pyramid (visibility_structs.h PyramidConstants, cull_structs.h
// CullCamera): each texel keeps the farthest (smallest, reversed Z) depth of the 2 x 2 texels under it,
// clamped at the level's edge; level 0 reads the visibility buffer's depth bits (0 where nothing was
// drawn: the far plane, which hides nothing).
#include "pass_bindings.h"
#include "visibility_structs.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kPyramidBindingVisibility, std430) readonly buffer VisibilityBlock { uvec2 visibility[]; };
layout(set = kPassSet, binding = kPyramidBindingTexels, std430) buffer PyramidBlock { float pyramid[]; };
layout(push_constant) uniform PyramidConstantsBlock { PyramidConstants constants; };

float sourceDepth(uvec2 texel) {
    uint index = texel.y * constants.sourceWidth + texel.x;
    if (constants.fromVisibility != 0u) return uintBitsToFloat(visibility[index].y);  // the word's high half
    return pyramid[constants.sourceOffset + index];
}

void main() {
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(texel, uvec2(constants.targetWidth, constants.targetHeight)))) return;
    uvec2 last = uvec2(constants.sourceWidth, constants.sourceHeight) - 1u;
    float farthest = min(min(sourceDepth(min(texel * 2u, last)), sourceDepth(min(texel * 2u + uvec2(1u, 0u), last))),
                         min(sourceDepth(min(texel * 2u + uvec2(0u, 1u), last)), sourceDepth(min(texel * 2u + 1u, last))));
    pyramid[constants.targetOffset + texel.y * constants.targetWidth + texel.x] = farthest;
}
