#version 460
// Spot and point lights' virtual page marking (render/virtual_face_mark_pass.h) from the main view's
// depth texture: one invocation per pixel (virtual_face_mark.glsl).
#include "virtual_face_mark.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kFaceMarkBindingDepth) uniform sampler2D sceneDepth;

void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= mark.width || p.y >= mark.height) return;
    markFacePixel(p, texelFetch(sceneDepth, ivec2(p), 0).r);
}
