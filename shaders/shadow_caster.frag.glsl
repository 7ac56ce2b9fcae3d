#version 460
// Alpha-aware shadow casters (Catlike Coding "Directional Shadows": Shadow Modes, Clipped Shadows,
// Dithered Shadows): `clip` materials drop texels below the alpha cutoff, `dither` materials drop them
// with probability 1 - alpha using interleaved gradient noise.
// Opaque (`on`) casters use a depth-only pipeline without this shader; `off` casters are not drawn.
#include "bindings.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 1) flat in uint inInstance;

void main() {
    MaterialData material = materials[instances[inInstance].materialIndex];
    // The level rule of the compute rasterizer too (bindings.glsl textureLevel).
    float level = material.baseColorTexture != 0u ? textureLevel(material.baseColorTexture - 1u, dFdx(inUv), dFdy(inUv)) : 0.0;
    float alpha = materialBaseColorLod(material, inUv, level).a;
    if (material.shadowMode == kShadowModeClip && alpha < material.alphaCutoff) discard;
    if (material.shadowMode == kShadowModeDither && alpha < interleavedGradientNoise(gl_FragCoord.xy)) discard;
}
