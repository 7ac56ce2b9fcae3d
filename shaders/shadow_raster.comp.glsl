#version 460
// Compute rasterizer, pass 1 (shadow_raster.glsl): one workgroup per meshlet (at most kRasterBatch
// triangles) of a slot of a tile's visible list (the GPU culling pass's output), its threads over the
// triangles; a meshlet whose box lies outside the tile is skipped whole (render.meshletCulling). Small
// pieces are rasterized by their thread; large ones are queued, set up, for the chunked passes.
#include "pass_bindings.h"
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kRasterBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = kPassSet, binding = kRasterBindingVisibleInstances, std430) readonly buffer VisibleBlock { uint visibleInstances[]; };

shared mat4 clipFromObject;
shared bool meshletSkipped;

// Rasterizes a small piece at once; queues a large one, set up, for passes 2 and 3.
void rasterizeOrQueue(RasterTriangleSetup t, CullMesh mesh, float slopeBias) {
    t.materialIndex = mesh.materialIndex;
    t.alphaTested = isAlphaTested(mesh);
    if (boundsArea(t.bounds) > kRasterSmallArea) {
        uint queued = atomicAdd(counters.largeQueued, 1u);
        if (queued < raster.largeCapacity) largePieces[queued] = packPiece(t, slopeBias);
        else atomicAdd(counters.largeDropped, 1u);
        return;
    }
    for (int y = t.bounds.y; y <= t.bounds.w; ++y)
        for (int x = t.bounds.x; x <= t.bounds.z; ++x) rasterizeTexel(t, slopeBias, x, y);
}

void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint tileIndex;
    if (!rasterTile(gl_WorkGroupID.z, tileIndex)) return;  // z: the raster list's entry (instanceDispatch)
    uint instanceCount = cull.instanceCount, meshCount = cull.meshCount;
    uint meshSlot = meshOfWorkItem(item, meshCount);
    CullMesh mesh = cullMeshes[meshSlot];
    uint local = item - mesh.firstRasterItem;
    if (mesh.meshletCount == 0u || local >= mesh.instanceCount * mesh.meshletCount) return;  // past the last item
    uint instanceInMesh = local / mesh.meshletCount;
    if (instanceInMesh >= listCounts[tileIndex * meshCount + meshSlot]) return;  // culled slot
    uint instance = visibleInstances[tileIndex * instanceCount + mesh.firstListSlot + instanceInMesh];
    Meshlet meshlet = meshlets[mesh.firstMeshlet + local % mesh.meshletCount];
    CullTile tile = tiles[tileIndex];
    float slopeBias = tile.slopeBias;
    if (gl_LocalInvocationID.x == 0u) {
        clipFromObject = tile.clipFromWorld * instances[instance].worldFromObject;
        // Depth is clamped, not clipped (pancaking): only the tile's sides and a perspective tile's near w.
        meshletSkipped = raster.meshletCulling != 0u && meshletBoxOutside(clipFromObject, meshlet.osMin.xyz, meshlet.osMax.xyz,
                                                                  kMeshletSidesXY | kMeshletSideNearW);
        if (meshletSkipped) atomicAdd(counters.meshletsOutside, 1u);
    }
    barrier();
    if (meshletSkipped) return;
    uint lastTriangle = meshlet.firstTriangle + meshlet.triangleCount;
    for (uint triangle = meshlet.firstTriangle + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u) {
        RasterVertex v[3];
        fetchTriangle(mesh, triangle, clipFromObject, v);
        RasterTriangleSetup t;
        if (!needsClipping(v, kShadowClipPlanes)) {  // nearly always: no polygon array, nothing in local memory
            if (setupTriangle(tile.viewport, tile.scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh, slopeBias);
            continue;
        }
        RasterVertex polygon[kMaxClipped];
        int vertexCount = clipTriangle(v, kShadowClipPlanes, polygon);
        for (int i = 1; i + 1 < vertexCount; ++i)
            if (setupTriangle(tile.viewport, tile.scissor, polygon[0], polygon[i], polygon[i + 1], t)) rasterizeOrQueue(t, mesh, slopeBias);
    }
}
