// The compute rasterizer of shadow depth: what the hardware does for the shadow caster
// pass (shadow_caster.vert / .frag, depth clamp, no culling), done in compute so it runs on every SM.
// The same rules as Vulkan's rasterization, so both paths write the same depth:
// - triangles clipped to w > kNearW and to a guard band of kGuard viewports (as the hardware's own
//   clipping: coverage inside the viewport is unchanged), vertices to window coordinates with the
//   tile's viewport, snapped to 1/256 texel (8 sub-pixel bits, what NVIDIA and llvmpipe use);
// - coverage at texel centres by exact integer edge functions (32 x 32 -> 64-bit products) with the
//   top-left fill rule of a y-down framebuffer; both faces cast;
// - depth: window z interpolated linearly in window space (z/w for perspective tiles), plus the
//   tile's slope-scale bias times max(|dz/dx|, |dz/dy|), clamped to [0, 1] (shadow pancaking);
// - alpha-tested casters (`clip` and `dither` shadow modes) sample their texture at the
//   perspective-correct uv with the uv change to the next texel in x and y as gradients: the LOD rule
//   of shadow_caster.frag;
// - depth as float bits (all >= 0, so they order like the floats) into a buffer by atomicMin.
#ifndef PENUMBRA_SHADOW_RASTER_GLSL
#define PENUMBRA_SHADOW_RASTER_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#include "pass_bindings.h"
#include "cull_structs.h"
#include "raster_mesh.glsl"

layout(set = kPassSet, binding = kShadowRasterBindingCullFrame, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = kPassSet, binding = kShadowRasterBindingAtlasDepth, std430) buffer DepthBlock { uint atlasDepth[]; };  // depthSide^2 float bits
// The culling pass's tiles and the entries this pass draws (cull_structs.h: CPU- or GPU-written lists).
layout(set = kPassSet, binding = kShadowRasterBindingTiles, std430) readonly buffer CullTileBlock {
    CullTileListHeader tileList;
    CullTile tiles[];
};
layout(set = kPassSet, binding = kShadowRasterBindingRasterList, std430) readonly buffer RasterTileBlock {
    RasterTileListHeader rasterList;
    uint rasterEntries[];  // culling tile of each entry
};

// Culling tile drawn by entry `i` of the raster list; false past its count (the dispatch's z is the count).
bool rasterTile(uint i, out uint tile) {
    tile = i < rasterList.count ? rasterEntries[i] : 0u;
    return i < rasterList.count && tile < tileList.count;
}

// The shadow modes as shadow_caster.frag: clip below the cutoff, dither by interleaved gradient noise.
bool alphaKeeps(RasterTriangleSetup t, vec3 weights, int x, int y) {
    MaterialData material = materials[t.materialIndex];
    float alpha = rasterBaseAlpha(t, weights, ivec2(x, y));
    if (material.shadowMode == kShadowModeClip && alpha < material.alphaCutoff) return false;
    if (material.shadowMode == kShadowModeDither && alpha < interleavedGradientNoise(vec2(x, y) + 0.5)) return false;
    return true;
}

void rasterizeTexel(RasterTriangleSetup t, float slopeBias, int x, int y) {
    ivec2 p = texelCentre(x, y);
    if (!insideEdge(t.p[1], t.p[2], p) || !insideEdge(t.p[2], t.p[0], p) || !insideEdge(t.p[0], t.p[1], p)) return;
    vec3 weights = planeWeights(t, x, y);
    if (t.alphaTested && !alphaKeeps(t, weights, x, y)) return;
    float z = dot(weights, t.z) + slopeBias * max(abs(t.depthSlope.x), abs(t.depthSlope.y));
    z = clamp(z, 0.0, 1.0);
    // A plain read first: far-away casters put thousands of triangles on one texel, and most of them
    // lie behind what is there already (the early depth test of the hardware path).
    uint texel = uint(y) * raster.depthSide + uint(x), bits = floatBitsToUint(z);
    if (bits < atlasDepth[texel]) atomicMin(atlasDepth[texel], bits);
}

bool isAlphaTested(CullMesh mesh) { return materials[mesh.materialIndex].shadowMode != kShadowModeOn; }

// The planes a shadow tile clips to (depth is clamped, not clipped: pancaking).
const uint kShadowClipPlanes = kClipNearW | kClipGuard;

#endif
