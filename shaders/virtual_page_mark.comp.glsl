#version 460
// Virtual shadow map page marking (render/virtual_page_mark_pass.h) from the main view's depth texture:
// one invocation per pixel sets the request bit of every clipmap page its shadow lookup will read
// (virtual_page_mark.glsl).
#include "virtual_page_mark.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kPageMarkBindingDepth) uniform sampler2D sceneDepth;

void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= mark.width || p.y >= mark.height) return;
    markPixel(p, texelFetch(sceneDepth, ivec2(p), 0).r);
}
