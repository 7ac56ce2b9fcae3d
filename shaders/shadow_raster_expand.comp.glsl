#version 460
// Compute rasterizer, pass 0b (shadow_raster.glsl): the work of pass 1. One invocation per slot of a
// drawn tile's culled list (tile = the raster list's entry in z): a slot its culling filled turns
// into work items (RasterWorkItem) of at most kRasterMeshletsPerItem of the instance's meshlets,
// appended to the work queue; the instances of a mesh of one small meshlet share packed items
// instead (CullMesh.packedInstances to an item). An instance's items hold the meshlets of the level of
// detail its size in the tile asks for (shadowLod). Pass 1 then runs one workgroup per item, so its
// dispatch holds only the meshlets a tile draws, not every meshlet of the scene per tile.
#include "pass_bindings.h"
#include "shadow_raster.glsl"

layout(local_size_x = kRasterExpandGroup) in;

layout(set = kPassSet, binding = kShadowRasterBindingWork, std430) writeonly buffer WorkBlock { RasterWorkItem work[]; };

void main() {
    uint slot = gl_GlobalInvocationID.x, tileIndex;
    uint instanceCount = cull.instanceCount, meshCount = cull.meshCount;
    if (slot >= instanceCount || meshCount == 0u || !rasterTile(gl_WorkGroupID.z, tileIndex)) return;
    uint meshSlot = meshOfRun(slot, meshCount, true);
    CullMesh mesh = cullMeshes[meshSlot];
    uint listed = listCounts[tileIndex * meshCount + meshSlot], local = slot - mesh.firstListSlot;
    if (local >= listed || mesh.meshletCount == 0u) return;
    uint packed = mesh.packedInstances;
    if (packed > 1u) {  // one item for this slot and the next packed - 1 of the list
        if (local % packed != 0u) return;
        uint item = atomicAdd(counters.workQueued, 1u);
        if (item < raster.workCapacity) work[item] = RasterWorkItem(slot, tileIndex, meshSlot, kRasterPackedItem | min(packed, listed - local));
        else atomicAdd(counters.workDropped, 1u);
        return;
    }
    // tileIndex is the workgroup's: a uniform index into the buffer array.
    uint instance = visibleLists[visibleListBuffer(tileIndex, raster.listsPerBuffer)]
                        .entries[visibleListStart(tileIndex, raster.listsPerBuffer, instanceCount) + slot];
    uint level = shadowLod(meshSlot, instanceWorldFromObject(instances[instance]), tiles[tileIndex]);
    uint items = (lodMeshlets(meshSlot, level).y + kRasterMeshletsPerItem - 1u) / kRasterMeshletsPerItem;
    uint first = atomicAdd(counters.workQueued, items);
    uint kept = first < raster.workCapacity ? min(items, raster.workCapacity - first) : 0u;
    if (level > 0u) atomicAdd(counters.lodItems, kept);
    for (uint i = 0u; i < kept; ++i)
        work[first + i] = RasterWorkItem(instance, tileIndex, meshSlot, (level << kRasterLodShift) | (i * kRasterMeshletsPerItem));
    if (kept < items) atomicAdd(counters.workDropped, items - kept);
}
