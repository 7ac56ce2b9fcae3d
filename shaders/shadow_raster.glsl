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

// The culling pass's visible lists (cull_structs.h): how many instances each (tile, mesh) kept, and the lists.
layout(set = kPassSet, binding = kRasterBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = kPassSet, binding = kRasterBindingVisibleInstances, std430) readonly buffer VisibleBlock { uint entries[]; }
    visibleLists[kVisibleListBuffers];  // split over buffers: index by a workgroup-uniform list

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

// Texel (x, y), whose centre the piece covers: its depth, if the material keeps it.
void coveredTexel(RasterTriangleSetup t, float slopeBias, int x, int y) {
    vec3 weights = planeWeights(t, x, y);
    if (t.alphaTested && !alphaKeeps(t, weights, x, y)) return;
    float z = dot(weights, t.z) + slopeBias * max(abs(t.depthSlope.x), abs(t.depthSlope.y));
    z = clamp(z, 0.0, 1.0);
    // A plain read first: far-away casters put thousands of triangles on one texel, and most of them
    // lie behind what is there already (the early depth test of the hardware path).
    uint texel = uint(y) * raster.depthSide + uint(x), bits = floatBitsToUint(z);
    if (bits < atlasDepth[texel]) atomicMin(atlasDepth[texel], bits);
}

void rasterizeTexel(RasterTriangleSetup t, float slopeBias, int x, int y) {
    ivec2 p = texelCentre(x, y);
    if (insideEdge(t.p[1], t.p[2], p) && insideEdge(t.p[2], t.p[0], p) && insideEdge(t.p[0], t.p[1], p))
        coveredTexel(t, slopeBias, x, y);
}

// Texels of a piece walked by one thread: the texels of `rect` (inclusive, inside the piece's bounds).
// The edge functions are exact in 32-bit integers when the triangle is small enough: a texel centre of
// the bounds lies at most 257 sub-texels outside the vertices' box, so with that box's extent (X, Y)
// every value is below X (Y + 257) + Y (X + 257) (< 2^31 for any unclipped piece of up to ~16K texels);
// they are then stepped by one addition per texel (Pineda, "A parallel algorithm for polygon
// rasterization", 1988). Else each texel takes insideEdge's exact 64-bit products.
bool edgesFitInt32(RasterTriangleSetup t) {
    ivec2 extent = max(max(t.p[0], t.p[1]), t.p[2]) - min(min(t.p[0], t.p[1]), t.p[2]);
    return float(extent.x) * float(extent.y + 257) + float(extent.y) * float(extent.x + 257) < 2.0e9;
}

// Edge a->b at sub-texel point p, less one where the top-left rule leaves the edge out.
int edgeAt(ivec2 a, ivec2 b, ivec2 p) {
    int value = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    return topLeft(a, b) ? value : value - 1;
}

// insideEdge's three edges ((p1, p2), (p2, p0), (p0, p1)) at p: covered <=> all >= 0. Exact when edgesFitInt32.
ivec3 edgesAt(RasterTriangleSetup t, ivec2 p) {
    return ivec3(edgeAt(t.p[1], t.p[2], p), edgeAt(t.p[2], t.p[0], p), edgeAt(t.p[0], t.p[1], p));
}
ivec3 edgeStepX(RasterTriangleSetup t) { return ivec3(t.p[1].y - t.p[2].y, t.p[2].y - t.p[0].y, t.p[0].y - t.p[1].y) * 256; }
ivec3 edgeStepY(RasterTriangleSetup t) { return ivec3(t.p[2].x - t.p[1].x, t.p[0].x - t.p[2].x, t.p[1].x - t.p[0].x) * 256; }

void rasterizeRect(RasterTriangleSetup t, float slopeBias, ivec4 rect) {
    if (!edgesFitInt32(t)) {
        for (int y = rect.y; y <= rect.w; ++y)
            for (int x = rect.x; x <= rect.z; ++x) rasterizeTexel(t, slopeBias, x, y);
        return;
    }
    ivec3 rowEdge = edgesAt(t, texelCentre(rect.x, rect.y)), stepX = edgeStepX(t), stepY = edgeStepY(t);
    for (int y = rect.y; y <= rect.w; ++y, rowEdge += stepY) {
        ivec3 edge = rowEdge;
        for (int x = rect.x; x <= rect.z; ++x, edge += stepX)
            if (all(greaterThanEqual(edge, ivec3(0)))) coveredTexel(t, slopeBias, x, y);
    }
}

// Whether `rect` lies wholly outside one of the piece's edges (its four corner centres do: the edge
// function is linear), so that it holds no covered texel. Only when edgesFitInt32.
bool rectOutside(RasterTriangleSetup t, ivec4 rect) {
    ivec3 corner = edgesAt(t, texelCentre(rect.x, rect.y));
    ivec3 acrossX = edgeStepX(t) * (rect.z - rect.x), acrossY = edgeStepY(t) * (rect.w - rect.y);
    ivec3 highest = max(max(corner, corner + acrossX), max(corner + acrossY, corner + acrossX + acrossY));
    return any(lessThan(highest, ivec3(0)));
}

// Pass 1's sizes (shadow_raster.comp): a piece whose bounds cover at most kShadowSmallArea texels is
// rasterized by its thread, at most kShadowMediumArea by its workgroup in blocks of kShadowBlock^2
// texels, more in chunks.
const uint kShadowSmallArea = 32u, kShadowMediumArea = 2048u;
const int kShadowBlock = 4;

bool isAlphaTested(CullMesh mesh) { return materials[mesh.materialIndex].shadowMode != kShadowModeOn; }

// The level (0: the full mesh, l: simplified level l, scene/meshlets.h) an instance of `mesh` is drawn
// with in `tile`: the coarsest whose object-space error, projected where the instance's bounding sphere
// comes nearest the light (w), is at most raster.lodErrorTexels texels of the tile. The rows of
// clipFromObject carry the instance's scale; an orthographic tile's w is 1 everywhere. The level arrays
// are read from the buffer, not from a copy of the mesh: a copy indexed by a variable costs every item
// of the rasterizer registers.
uint shadowLod(uint meshSlot, mat4 worldFromObject, CullTile tile) {
    uint lodCount = cullMeshes[meshSlot].lodCount;
    if (lodCount == 0u || !(raster.lodErrorTexels > 0.0) || isAlphaTested(cullMeshes[meshSlot])) return 0u;
    vec4 osSphere = cullMeshes[meshSlot].osSphere;
    mat4 clipFromObject = tile.clipFromWorld * worldFromObject;
    vec3 rowX = vec3(clipFromObject[0][0], clipFromObject[1][0], clipFromObject[2][0]);
    vec3 rowY = vec3(clipFromObject[0][1], clipFromObject[1][1], clipFromObject[2][1]);
    vec3 rowW = vec3(clipFromObject[0][3], clipFromObject[1][3], clipFromObject[2][3]);
    float nearW = dot(rowW, osSphere.xyz) + clipFromObject[3][3] - length(rowW) * osSphere.w;
    if (!(nearW > 1e-6)) return 0u;  // the light sits inside its bounds
    float texelsPerUnit = 0.5 * max(length(rowX) * tile.viewport.z, length(rowY) * tile.viewport.w) / nearW;
    for (uint level = lodCount; level > 0u; --level)
        if (cullMeshes[meshSlot].lodError[level - 1u] * texelsPerUnit <= raster.lodErrorTexels) return level;
    return 0u;
}

// A level's meshlets: the first (in the scene's meshlets) and how many.
uvec2 lodMeshlets(uint meshSlot, uint level) {
    return level == 0u ? uvec2(cullMeshes[meshSlot].firstMeshlet, cullMeshes[meshSlot].meshletCount)
                       : uvec2(cullMeshes[meshSlot].lodFirstMeshlet[level - 1u], cullMeshes[meshSlot].lodMeshletCount[level - 1u]);
}

// The planes a shadow tile clips to (depth is clamped, not clipped: pancaking).
const uint kShadowClipPlanes = kClipNearW | kClipGuard;

#endif
