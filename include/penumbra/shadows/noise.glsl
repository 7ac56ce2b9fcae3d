#ifndef PENUMBRA_SHADOWS_NOISE_GLSL
#define PENUMBRA_SHADOWS_NOISE_GLSL
// Interleaved gradient noise (Jimenez 2014), the dither pattern Unity's pipelines use for dithered
// shadows and cascade blending (Catlike Coding "Directional Shadows": Dithered Transition, Dithered Shadows).
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}
#endif
