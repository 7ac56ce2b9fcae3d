// Contact-hardening soft shadows ("Percentage-Closer Soft Shadows", Fernando 2005) for lights with shadows
// "pcss": a blocker search averages the depth of the occluders around the receiver, similar triangles turn
// receiver and blocker distances and the light's size into the penumbra's width, and a disk of bilinear
// compares that wide gives the visibility. Every compare uses the receiver plane's depth at the tap
// (bias.glsl) at each texel's centre (tent.glsl penumbraCompareBilinear), so wide kernels bring
// no acne.
#ifndef PENUMBRA_SHADOW_PCSS_GLSL
#define PENUMBRA_SHADOW_PCSS_GLSL
#include "bias.glsl"
#include "shadow_structs.h"
#include "tent.glsl"

const int kPcssSearchSamples = 32;
const int kPcssFilterSamples = 64;

// Sample i of n on the unit disk: Vogel's golden-angle spiral (area-uniform, no per-pixel noise, so
// stable while the camera moves).
vec2 pcssDisk(int i, int n) {
    float r = sqrt((float(i) + 0.5) / float(n));
    float theta = float(i) * 2.39996323;
    return r * vec2(cos(theta), sin(theta));
}

// How a tile's depths turn into distances along the light, and how wide the penumbra is.
struct PcssLight {
    float perspective;  // 1 perspective (spot, point), 0 orthographic (directional)
    // orthographic: x = world metres per unit of depth, y = tan(the sun's angular radius), z = world texel;
    // perspective: x = emitter radius (m), y = near, z = far, w = world texel per metre of distance.
    vec4 params;
};

float pcssDistance(PcssLight light, float depth) {
    if (light.perspective < 0.5) return depth * light.params.x;
    float near = light.params.y, far = light.params.z;
    return near * far / (far - depth * (far - near));  // inverse of perspectiveClipFromLight's depth
}

// Full penumbra width in texels at the receiver for a blocker at depth zBlocker (similar triangles).
float pcssPenumbraTexels(PcssLight light, float zReceiver, float zBlocker) {
    float dR = pcssDistance(light, zReceiver), dB = pcssDistance(light, zBlocker);
    if (light.perspective < 0.5) return 2.0 * (dR - dB) * light.params.y / light.params.z;
    return 2.0 * light.params.x * (dR - dB) / (max(dB, 1e-6) * light.params.w * dR);
}

// The mean depth of the blockers within searchRadius texels of u (texel units; z = the receiver plane's
// depth at u, g its gradient), or -1 when there is none.
float pcssBlockerDepth(sampler2D atlas, vec2 u, float z, vec2 g, vec4 texelSize, vec4 uvBounds, float searchRadius) {
    float blockerSum = 0.0, blockers = 0.0;
    for (int i = 0; i < kPcssSearchSamples; ++i) {
        vec2 uv = clamp((u + pcssDisk(i, kPcssSearchSamples) * searchRadius) * texelSize.xy, uvBounds.xy, uvBounds.zw);
        float stored = textureLod(atlas, uv, 0.0).r;
        vec2 texelCentre = floor(uv * texelSize.zw) + 0.5;  // the plane's depth where that texel was drawn
        float isBlocker = stored < z + dot(g, texelCentre - u) ? 1.0 : 0.0;
        blockerSum += isBlocker * stored;
        blockers += isBlocker;
    }
    return blockers > 0.0 ? blockerSum / blockers : -1.0;
}

// Visibility in [0, 1] of the receiver at uvDepth (atlas u, v, biased depth; g = the plane's depth
// gradient per texel), taps kept inside uvBounds (the tile).
float pcssShadow(sampler2D atlas, vec3 uvDepth, vec2 g, vec4 texelSize, vec4 uvBounds,
                 PcssLight light) {
    vec2 u = uvDepth.xy * texelSize.zw;
    float z = uvDepth.z;
    // Blockers can lie anywhere between the receiver and the light: search the width a blocker at the
    // near plane would give, within kPcssMaxRadiusTexels.
    float searchRadius = clamp(0.5 * pcssPenumbraTexels(light, z, 0.0), 1.0, kPcssMaxRadiusTexels);
    float blocker = pcssBlockerDepth(atlas, u, z, g, texelSize, uvBounds, searchRadius);
    if (blocker < 0.0) return 1.0;
    float radius = clamp(0.5 * pcssPenumbraTexels(light, z, blocker), 0.5, kPcssMaxRadiusTexels);
    float lit = 0.0;
    for (int i = 0; i < kPcssFilterSamples; ++i) {
        vec2 uv = clamp((u + pcssDisk(i, kPcssFilterSamples) * radius) * texelSize.xy, uvBounds.xy, uvBounds.zw);
        lit += penumbraCompareBilinear(atlas, uv * texelSize.zw, uvDepth, u, texelSize, g, true);
    }
    return lit / float(kPcssFilterSamples);
}
#endif
