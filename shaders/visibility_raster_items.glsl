// Visibility rasterizer, pass 1 (visibility_raster.glsl), included by its two pipelines:
// visibility_raster.comp takes one workgroup per meshlet (at most kRasterBatch triangles) of a slot of
// one of the main view's culling lists (cull_structs.h: the camera
// frustum and occlusion culled, blended materials left out), as the shadow rasterizer reads a tile's
// list. With render.meshletCulling a meshlet outside the view, or one whose every triangle faces away
// from the camera (single-sided materials), is skipped whole. Small pieces are rasterized by their
// thread; large ones are queued, set up, for passes 2 and 3 (or rasterized here when the queue is full).
// visibility_raster_packed.comp (PENUMBRA_PACKED_ITEMS) takes the items of meshes of one small meshlet
// (CullMesh.packedInstances > 1): up to that many instances each. Both dispatch over every item and
// leave the other's items: one shader with both paths made the meshlet items 40 % slower on an H100
// (the engine field's main view 0.78 -> 1.10 ms), presumably by the packed path's registers.
#ifndef PENUMBRA_VISIBILITY_RASTER_ITEMS_GLSL
#define PENUMBRA_VISIBILITY_RASTER_ITEMS_GLSL
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
bool skipMeshlet(Meshlet meshlet, uint instance, mat4 clipFromInstance, bool doubleSided) {
    if (meshletBoxOutside(clipFromInstance, meshlet.osMin.xyz, meshlet.osMax.xyz, kMeshletSidesXY | kMeshletSidesDepth)) {
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

// One triangle of an instance: culled if it faces away, else set up (clipped where it must be) and
// rasterized or queued. Both pipelines' loops call it.
void rasterizeTriangle(CullMesh mesh, uint triangle, uint instance, mat4 clipFromInstance, bool doubleSided) {
    vec4 viewport = vec4(0.0, 0.0, float(viewWidth()), float(viewHeight()));
    uvec4 scissor = uvec4(0u, 0u, viewWidth(), viewHeight());
    RasterVertex v[3];
    fetchTriangle(mesh, triangle, clipFromInstance, v);
    if (!facesShown(v, doubleSided)) return;
    uint payload = ((instance << raster.triangleBits) | triangle) + 1u;
    RasterTriangleSetup t;
    if (!needsClipping(v, kViewClipPlanes)) {
        if (setupTriangle(viewport, scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh.materialIndex, payload);
        return;
    }
    RasterVertex polygon[kMaxClipped];
    int vertexCount = clipTriangle(v, kViewClipPlanes, polygon);
    for (int i = 1; i + 1 < vertexCount; ++i)
        if (setupTriangle(viewport, scissor, polygon[0], polygon[i], polygon[i + 1], t))
            rasterizeOrQueue(t, mesh.materialIndex, payload);
}

#ifdef PENUMBRA_PACKED_ITEMS
// A packed item's instances whose meshlet is drawn (not skipped by render.meshletCulling), with their matrices.
shared uint packedDrawn;
shared uint packedInstance[kRasterPackInstances];
shared mat4 packedClipFromObject[kRasterPackInstances];

// A packed item (CullMesh.packedInstances > 1): up to that many instances of a one-meshlet mesh from
// list slot `first`. A thread per instance tests its meshlet (as a meshlet item's first thread does)
// and keeps the drawn ones with their matrices; then a thread per (kept instance, triangle).
void rasterizePacked(CullMesh mesh, uint list, uint first, uint listed, bool doubleSided) {
    Meshlet meshlet = meshlets[mesh.firstMeshlet];
    uint count = min(mesh.packedInstances, listed - first);
    if (gl_LocalInvocationID.x == 0u) packedDrawn = 0u;
    barrier();
    if (gl_LocalInvocationID.x < count) {
        uint listBuffer = visibleListBuffer(list, raster.listsPerBuffer);
        uint listStart = visibleListStart(list, raster.listsPerBuffer, raster.instanceCount) + mesh.firstListSlot + first;
        uint instance = visibleLists[listBuffer].entries[listStart + gl_LocalInvocationID.x];
        mat4 clipFromInstance = frame.clipFromWorld * instanceWorldFromObject(instances[instance]);
        if (raster.meshletCulling == 0u || !skipMeshlet(meshlet, instance, clipFromInstance, doubleSided)) {
            uint kept = atomicAdd(packedDrawn, 1u);
            packedInstance[kept] = instance;
            packedClipFromObject[kept] = clipFromInstance;
        }
    }
    barrier();
    uint triangles = meshlet.triangleCount, total = packedDrawn * triangles;
    for (uint i = gl_LocalInvocationID.x; i < total; i += 64u)
        rasterizeTriangle(mesh, meshlet.firstTriangle + i % triangles, packedInstance[i / triangles],
                          packedClipFromObject[i / triangles], doubleSided);
}

void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint meshSlot = meshOfRun(item, raster.meshSlots, false);
    CullMesh mesh = cullMeshes[meshSlot];
    if (mesh.packedInstances <= 1u) return;  // visibility_raster.comp's
    uint list = raster.list, first = (item - mesh.firstRasterItem) * mesh.packedInstances;
    uint listed = min(listCounts[list * raster.meshSlots + meshSlot], mesh.instanceCount);
    if (first >= listed) return;  // culled slots
    bool doubleSided = (materials[mesh.materialIndex].flags & kMaterialDoubleSided) != 0u;
    rasterizePacked(mesh, list, first, listed, doubleSided);
}
#else
void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint meshSlot = meshOfRun(item, raster.meshSlots, false);
    CullMesh mesh = cullMeshes[meshSlot];
    uint local = item - mesh.firstRasterItem;
    if (mesh.packedInstances > 1u) return;  // visibility_raster_packed.comp's
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
        meshletSkipped = raster.meshletCulling != 0u && skipMeshlet(meshlet, instance, clipFromObject, doubleSided);
    }
    barrier();
    if (meshletSkipped) return;
    uint lastTriangle = meshlet.firstTriangle + meshlet.triangleCount;
    for (uint triangle = meshlet.firstTriangle + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u)
        rasterizeTriangle(mesh, triangle, instance, clipFromObject, doubleSided);
}
#endif

#endif
