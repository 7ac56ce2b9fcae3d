#version 460
// Virtual shadow map page marking (render/virtual_page_mark_pass.h) from the visibility buffer, before
// its resolve shades the pixels: each pixel's 64-bit word holds its reversed-Z depth's bits in the high
// half (visibility_raster.glsl), read here as the second of two 32-bit words (little-endian).
#include "virtual_page_mark.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = kPassSet, binding = kPageMarkBindingVisibility, std430) readonly buffer PageMarkVisibilityBlock {
    uvec2 visibilityWords[];
};

void main() {
    const uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= mark.width || p.y >= mark.height) return;
    markPixel(p, uintBitsToFloat(visibilityWords[p.y * mark.width + p.x].y));
}
