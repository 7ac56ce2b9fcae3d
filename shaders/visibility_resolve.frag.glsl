#version 460
// Visibility-buffer resolve, fragment twin of visibility_resolve.comp for CPU devices
// (render/visibility_pass.h): a full-screen triangle whose fragments shade their pixel's triangle with
// the same functions (visibility_surface.glsl) and write colour and depth to the targets directly.
#include "visibility_surface.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uvec2 word = visibility[pixel.y * constants.width + pixel.x];
    gl_FragDepth = uintBitsToFloat(word.y);
    outColor = word.x == 0u ? backgroundPixel(pixel) : shadeVisiblePixel(word.x, pixel);
}
