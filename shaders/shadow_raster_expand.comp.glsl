#version 460
// Compute rasterizer, pass 0b (shadow_raster.glsl): the work of pass 1. One invocation per slot of a
// drawn tile's culled list (tile = the raster list's entry in z): a slot its culling filled turns
// into work items (RasterWorkItem) of at most kRasterMeshletsPerItem of the instance's meshlets,
// appended to the work queue. Pass 1 then runs one workgroup per item, so its dispatch holds only the
// meshlets a tile draws, not every meshlet of the scene per tile.
#include "pass_bindings.h"
#include "shadow_raster.glsl"

layout(local_size_x = kRasterExpandGroup) in;

layout(set = kPassSet, binding = kRasterBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
layout(set = kPassSet, binding = kRasterBindingVisibleInstances, std430) readonly buffer VisibleBlock { uint entries[]; }
    visibleLists[kVisibleListBuffers];  // cull_structs.h: the lists split over buffers
layout(set = kPassSet, binding = kShadowRasterBindingWork, std430) writeonly buffer WorkBlock { RasterWorkItem work[]; };

void main() {
    uint slot = gl_GlobalInvocationID.x, tileIndex;
    uint instanceCount = cull.instanceCount, meshCount = cull.meshCount;
    if (slot >= instanceCount || meshCount == 0u || !rasterTile(gl_WorkGroupID.z, tileIndex)) return;
    uint meshSlot = meshOfRun(slot, meshCount, true);
    CullMesh mesh = cullMeshes[meshSlot];
    if (slot - mesh.firstListSlot >= listCounts[tileIndex * meshCount + meshSlot] || mesh.meshletCount == 0u) return;
    // tileIndex is the workgroup's: a uniform index into the buffer array.
    uint instance = visibleLists[visibleListBuffer(tileIndex, raster.listsPerBuffer)]
                        .entries[visibleListStart(tileIndex, raster.listsPerBuffer, instanceCount) + slot];
    uint items = (mesh.meshletCount + kRasterMeshletsPerItem - 1u) / kRasterMeshletsPerItem;
    uint first = atomicAdd(counters.workQueued, items);
    uint kept = first < raster.workCapacity ? min(items, raster.workCapacity - first) : 0u;
    for (uint i = 0u; i < kept; ++i) work[first + i] = RasterWorkItem(instance, tileIndex, meshSlot, i * kRasterMeshletsPerItem);
    if (kept < items) atomicAdd(counters.workDropped, items - kept);
}
