#version 460
// Visibility-buffer resolve (visibility_structs.h), compute: one thread per pixel reads the
// nearest triangle the compute rasterizer kept and shades it with shade_surface.glsl, the forward
// pass's own functions (visibility_surface.glsl), or the background where there is none. Writes the
// colour (RGBA8, sRGB-encoded for sRGB targets) and the depth, copied into the targets (the depth only
// for a later pass that reads it: blended materials, the tight cascade fit).
#include "pass_bindings.h"
#include "visibility_surface.glsl"

layout(local_size_x = kResolveGroupSize, local_size_y = kResolveGroupSize) in;

layout(set = kPassSet, binding = kResolveBindingColor, rgba8) uniform writeonly image2D resolvedColor;
layout(set = kPassSet, binding = kResolveBindingDepth, std430) writeonly buffer DepthBlock { float resolvedDepth[]; };

vec3 srgbEncode(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= constants.width || pixel.y >= constants.height) return;
    uint index = pixel.y * constants.width + pixel.x;
    uvec2 word = visibility[index];
    resolvedDepth[index] = uintBitsToFloat(word.y);
    if (word.x == 0u) {  // nothing drawn: the clear colour as given, or the gradient (encoded as shading is)
        vec4 background = backgroundPixel(pixel);
        if (constants.backgroundGradient != 0u && constants.encodeSrgb != 0u) background.rgb = srgbEncode(background.rgb);
        imageStore(resolvedColor, ivec2(pixel), background);
        return;
    }
    vec4 color = shadeVisiblePixel(word.x, pixel);
    if (constants.encodeSrgb != 0u) color.rgb = srgbEncode(color.rgb);
    imageStore(resolvedColor, ivec2(pixel), color);
}
