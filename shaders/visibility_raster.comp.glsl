#version 460
// Visibility rasterizer, pass 1 (visibility_raster.glsl): one workgroup per meshlet (at most
// kRasterBatch triangles) of a slot of one of the main view's culling lists (cull_structs.h: the camera
// frustum and occlusion culled, blended materials left out), as the shadow rasterizer reads a tile's
// list. With render.meshletCulling a meshlet outside the view, or one whose every triangle faces away
// from the camera (single-sided materials), is skipped whole. Small pieces are rasterized by their
// thread; large ones are queued, set up, for passes 2 and 3 (or rasterized here when the queue is full).
#include "pass_bindings.h"
#include "visibility_raster.glsl"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kRasterBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = kPassSet, binding = kRasterBindingVisibleInstances, std430) readonly buffer VisibleBlock { uint entries[]; }
    visibleLists[kVisibleListBuffers];  // cull_structs.h: the lists split over buffers

shared mat4 clipFromObject;
shared bool meshletSkipped;

void rasterizeOrQueue(RasterTriangleSetup t, uint materialIndex, uint payload) {
    t.materialIndex = materialIndex;
    t.alphaTested = materials[materialIndex].alphaMode == kAlphaMask;
    if (boundsArea(t.bounds) > kRasterSmallArea) {
        uint queued = atomicAdd(counters.largeQueued, 1u);
        if (queued < raster.largeCapacity) {
            largePieces[queued] = packViewPiece(t, payload);
            return;
        }
        atomicAdd(counters.largeDropped, 1u);  // full: this thread draws it (slower, nothing lost)
    }
    rasterizePiece(t, payload);
}

// Whether the meshlet draws nothing (counted): outside the view's sides or depth range, or, for a
// single-sided material on an instance that is not mirrored, every triangle facing away from the camera.
bool skipMeshlet(Meshlet meshlet, uint instance, bool doubleSided) {
    if (meshletBoxOutside(clipFromObject, meshlet.osMin.xyz, meshlet.osMax.xyz, kMeshletSidesXY | kMeshletSidesDepth)) {
        atomicAdd(counters.meshletsOutside, 1u);
        return true;
    }
    mat4 worldFromObject = instanceWorldFromObject(instances[instance]);
    if (doubleSided || determinant(mat3(worldFromObject)) <= 0.0) return false;
    vec3 osEye = meshletObjectEye(worldFromObject, frame.wsCameraPosition.xyz);
    if (!meshletFacesAway(meshlet.coneApex.xyz, meshlet.coneAxis, meshlet.coneCutoff, osEye)) return false;
    atomicAdd(counters.meshletsFacingAway, 1u);
    return true;
}

void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint meshSlot = meshOfRun(item, raster.meshSlots, false);
    CullMesh mesh = cullMeshes[meshSlot];
    uint local = item - mesh.firstRasterItem;
    if (mesh.meshletCount == 0u || local >= mesh.instanceCount * mesh.meshletCount) return;  // past the last item
    uint list = raster.list, instanceInMesh = local / mesh.meshletCount;
    if (instanceInMesh >= listCounts[list * raster.meshSlots + meshSlot]) return;  // culled slot
    uint instance = visibleLists[visibleListBuffer(list, raster.listsPerBuffer)]
                        .entries[visibleListStart(list, raster.listsPerBuffer, raster.instanceCount) + mesh.firstListSlot + instanceInMesh];
    Meshlet meshlet = meshlets[mesh.firstMeshlet + local % mesh.meshletCount];
    MaterialData material = materials[mesh.materialIndex];
    bool doubleSided = (material.flags & kMaterialDoubleSided) != 0u;
    if (gl_LocalInvocationID.x == 0u) {
        clipFromObject = frame.clipFromWorld * instanceWorldFromObject(instances[instance]);
        meshletSkipped = raster.meshletCulling != 0u && skipMeshlet(meshlet, instance, doubleSided);
    }
    barrier();
    if (meshletSkipped) return;
    vec4 viewport = vec4(0.0, 0.0, float(viewWidth()), float(viewHeight()));
    uvec4 scissor = uvec4(0u, 0u, viewWidth(), viewHeight());
    uint lastTriangle = meshlet.firstTriangle + meshlet.triangleCount;
    for (uint triangle = meshlet.firstTriangle + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u) {
        RasterVertex v[3];
        fetchTriangle(mesh, triangle, clipFromObject, v);
        if (!facesShown(v, doubleSided)) continue;
        uint payload = ((instance << raster.triangleBits) | triangle) + 1u;
        RasterTriangleSetup t;
        if (!needsClipping(v, kViewClipPlanes)) {
            if (setupTriangle(viewport, scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh.materialIndex, payload);
            continue;
        }
        RasterVertex polygon[kMaxClipped];
        int vertexCount = clipTriangle(v, kViewClipPlanes, polygon);
        for (int i = 1; i + 1 < vertexCount; ++i)
            if (setupTriangle(viewport, scissor, polygon[0], polygon[i], polygon[i + 1], t))
                rasterizeOrQueue(t, mesh.materialIndex, payload);
    }
}
