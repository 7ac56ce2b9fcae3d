#version 460
// Spot and point lights' virtual page marking (render/virtual_face_mark_pass.h) from the visibility
// buffer: each pixel's reversed-Z depth bits are the high half of its 64-bit word (visibility_raster.glsl).
#include "virtual_face_mark.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kFaceMarkBindingVisibility, std430) readonly buffer FaceMarkVisibilityBlock {
    uvec2 visibilityWords[];
};

void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= mark.width || p.y >= mark.height) return;
    markFacePixel(p, uintBitsToFloat(visibilityWords[p.y * mark.width + p.x].y));
}
