#version 460
// Compute rasterizer, pass 1 (shadow_raster.glsl): one workgroup per slot of a tile's visible list
// (the GPU culling pass's output), its threads over the instance's triangles. Small triangles are
// rasterized by their thread; large ones are queued for the chunked passes.
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 12, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = 0, binding = 13, std430) readonly buffer VisibleBlock { uint visibleInstances[]; };

// The mesh slot whose part of a tile's list holds `slot` (slots are grouped by mesh, in mesh order).
uint meshOfSlot(uint slot, uint meshCount) {
    uint lo = 0u, hi = meshCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (cullMeshes[mid].counts.x <= slot) lo = mid;
        else hi = mid - 1u;
    }
    return lo;
}

void main() {
    uint slot = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint tileIndex = raster.pass.x + gl_WorkGroupID.z;
    uint instanceCount = cull.counts.y, meshCount = cull.counts.z;
    if (slot >= instanceCount) return;
    uint meshSlot = meshOfSlot(slot, meshCount);
    CullMesh mesh = cullMeshes[meshSlot];
    if (slot - mesh.counts.x >= listCounts[tileIndex * meshCount + meshSlot]) return;  // culled slot
    uint instance = visibleInstances[tileIndex * instanceCount + slot];
    CullTile tile = cull.tiles[tileIndex];
    float slopeBias = tile.wsLightDirection.w;
    for (uint triangle = gl_LocalInvocationID.x; triangle < mesh.draw.x / 3u; triangle += 64u) {
        RasterTriangleSetup pieces[6];
        int count = setupPieces(tile, meshSlot, instance, triangle, pieces);
        bool large = false;
        for (int i = 0; i < count; ++i) large = large || boundsArea(pieces[i].bounds) > kRasterSmallArea;
        if (large) {
            uint queued = atomicAdd(counters.counts.x, 1u);
            if (queued < kRasterMaxLarge) largeTriangles[queued].ids = uvec4(tileIndex, instance, triangle, meshSlot);
            else atomicAdd(counters.counts.z, 1u);
            continue;
        }
        for (int i = 0; i < count; ++i)
            for (int y = pieces[i].bounds.y; y <= pieces[i].bounds.w; ++y)
                for (int x = pieces[i].bounds.x; x <= pieces[i].bounds.z; ++x) rasterizeTexel(pieces[i], slopeBias, x, y);
    }
}
