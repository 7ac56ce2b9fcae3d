#version 460
// Compute rasterizer, pass 1 (shadow_raster.glsl): one workgroup per work item (RasterWorkItem: up to
// kRasterMeshletsPerItem meshlets of one instance in one tile, queued by shadow_raster_expand.comp),
// its threads over each meshlet's triangles (at most kRasterBatch); a meshlet whose box lies outside
// the tile is skipped whole (render.meshletCulling). Small pieces are rasterized by their thread;
// large ones are queued, set up, for the chunked passes.
#include "pass_bindings.h"
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kShadowRasterBindingWork, std430) readonly buffer WorkBlock { RasterWorkItem work[]; };

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

void rasterizeMeshlet(CullMesh mesh, Meshlet meshlet, CullTile tile) {
    uint lastTriangle = meshlet.firstTriangle + meshlet.triangleCount;
    for (uint triangle = meshlet.firstTriangle + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u) {
        RasterVertex v[3];
        fetchTriangle(mesh, triangle, clipFromObject, v);
        RasterTriangleSetup t;
        if (!needsClipping(v, kShadowClipPlanes)) {  // nearly always: no polygon array, nothing in local memory
            if (setupTriangle(tile.viewport, tile.scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh, tile.slopeBias);
            continue;
        }
        RasterVertex polygon[kMaxClipped];
        int vertexCount = clipTriangle(v, kShadowClipPlanes, polygon);
        for (int i = 1; i + 1 < vertexCount; ++i)
            if (setupTriangle(tile.viewport, tile.scissor, polygon[0], polygon[i], polygon[i + 1], t))
                rasterizeOrQueue(t, mesh, tile.slopeBias);
    }
}

void main() {
    uint itemIndex = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (itemIndex >= min(counters.workQueued, raster.workCapacity)) return;  // past the last item (workDispatch)
    RasterWorkItem item = work[itemIndex];
    CullMesh mesh = cullMeshes[item.meshSlot];
    CullTile tile = tiles[item.tile];
    if (gl_LocalInvocationID.x == 0u) clipFromObject = tile.clipFromWorld * instanceWorldFromObject(instances[item.instance]);
    uint lastMeshlet = min(item.firstMeshlet + kRasterMeshletsPerItem, mesh.meshletCount);
    for (uint m = item.firstMeshlet; m < lastMeshlet; ++m) {
        Meshlet meshlet = meshlets[mesh.firstMeshlet + m];
        barrier();  // clipFromObject written; the last meshlet's threads done with meshletSkipped
        if (gl_LocalInvocationID.x == 0u) {
            // Depth is clamped, not clipped (pancaking): only the tile's sides and a perspective tile's near w.
            meshletSkipped = raster.meshletCulling != 0u && meshletBoxOutside(clipFromObject, meshlet.osMin.xyz, meshlet.osMax.xyz,
                                                                      kMeshletSidesXY | kMeshletSideNearW);
            if (meshletSkipped) atomicAdd(counters.meshletsOutside, 1u);
        }
        barrier();
        if (!meshletSkipped) rasterizeMeshlet(mesh, meshlet, tile);
    }
}
