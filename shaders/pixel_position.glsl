// The world position a pixel of the main view shows, from its reversed-Z depth: pixel centres, Vulkan NDC
// (y down), as shadows/visible_surfaces.h wsPositionFromDepth computes it on the CPU (the same float
// operations: the virtual shadow maps' page marking agrees with its CPU references).
#ifndef PENUMBRA_PIXEL_POSITION_GLSL
#define PENUMBRA_PIXEL_POSITION_GLSL

vec3 wsPositionOfPixel(mat4 worldFromClip, uvec2 p, uint width, uint height, float depth) {
    const float px = float(p.x) + 0.5, py = float(p.y) + 0.5;
    const vec4 clip = vec4(2.0 * px / float(width) - 1.0, 2.0 * py / float(height) - 1.0, depth, 1.0);
    const vec4 h = worldFromClip * clip;
    return h.xyz / h.w;
}
#endif
