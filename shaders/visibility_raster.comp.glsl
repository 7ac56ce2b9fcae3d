#version 460
// Visibility rasterizer, pass 1 (visibility_raster.glsl): one workgroup per batch of kRasterBatch
// triangles of a slot of one of the main view's culling lists (cull_structs.h: the camera frustum and
// occlusion culled, blended materials left out), as the shadow rasterizer reads a tile's list. Small
// pieces are rasterized by their thread; large ones are queued, set up, for passes 2 and 3 (or
// rasterized here when the queue is full).
#include "visibility_raster.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = kBindingViewListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = 0, binding = kBindingViewLists, std430) readonly buffer VisibleBlock { uint visibleInstances[]; };

shared mat4 clipFromObject;

void rasterizeOrQueue(RasterTriangleSetup t, uint materialIndex, uint payload) {
    t.materialIndex = materialIndex;
    t.alphaTested = materials[materialIndex].flags.z == kAlphaMask;
    if (boundsArea(t.bounds) > kRasterSmallArea) {
        uint queued = atomicAdd(counters.counts.x, 1u);
        if (queued < raster.capacity.x) {
            largePieces[queued] = packViewPiece(t, payload);
            return;
        }
        atomicAdd(counters.counts.z, 1u);  // full: this thread draws it (slower, nothing lost)
    }
    rasterizePiece(t, payload);
}

void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint meshSlot = meshOfWorkItem(item, raster.capacity.w);
    CullMesh mesh = cullMeshes[meshSlot];
    uint local = item - mesh.counts.z;
    if (mesh.counts.w == 0u || local >= mesh.counts.y * mesh.counts.w) return;  // past the last item
    uint list = raster.list.x, instanceInMesh = local / mesh.counts.w, batch = local % mesh.counts.w;
    if (instanceInMesh >= listCounts[list * raster.capacity.w + meshSlot]) return;  // culled slot
    uint instance = visibleInstances[list * raster.list.y + mesh.counts.x + instanceInMesh];
    MaterialData material = materials[mesh.draw.w];
    if (gl_LocalInvocationID.x == 0u) clipFromObject = frame.clipFromWorld * instances[instance].worldFromObject;
    barrier();
    bool doubleSided = (material.flags.y & kMaterialDoubleSided) != 0u;
    vec4 viewport = vec4(0.0, 0.0, float(viewWidth()), float(viewHeight()));
    uvec4 scissor = uvec4(0u, 0u, viewWidth(), viewHeight());
    uint lastTriangle = min((batch + 1u) * kRasterBatch, mesh.draw.x / 3u);
    for (uint triangle = batch * kRasterBatch + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u) {
        RasterVertex v[3];
        fetchTriangle(mesh, triangle, clipFromObject, v);
        if (!facesShown(v, doubleSided)) continue;
        uint payload = ((instance << raster.pass.z) | triangle) + 1u;
        RasterTriangleSetup t;
        if (!needsClipping(v, kViewClipPlanes)) {
            if (setupTriangle(viewport, scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh.draw.w, payload);
            continue;
        }
        RasterVertex polygon[kMaxClipped];
        int vertexCount = clipTriangle(v, kViewClipPlanes, polygon);
        for (int i = 1; i + 1 < vertexCount; ++i)
            if (setupTriangle(viewport, scissor, polygon[0], polygon[i], polygon[i + 1], t))
                rasterizeOrQueue(t, mesh.draw.w, payload);
    }
}
