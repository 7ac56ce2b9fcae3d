#version 460
// Compacts the (tile, mesh) lists of shadow_cull.comp into indirect draws (cull_structs.h): one
// invocation per (mesh, tile); a non-empty list becomes one VkDrawIndexedIndirectCommand drawing
// its instances, in the tile's opaque or alpha-tested list by the material's shadow mode
// (on, clip, dither; off casters are never listed), and counts into the tile's stats.
#include "pass_bindings.h"
#include "cull_structs.h"
#include "scene_structs.h"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kCullBindingFrame, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = kPassSet, binding = kCullBindingMeshes, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = kPassSet, binding = kCullBindingMaterials, std430) readonly buffer MaterialBlock { MaterialData materials[]; };
layout(set = kPassSet, binding = kCullBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
// [(tile * kCasterKinds + kind) * meshes + i] x 5 uints: indexCount, instanceCount, firstIndex,
// vertexOffset, firstInstance.
layout(set = kPassSet, binding = kDrawsBindingDrawCommands, std430) writeonly buffer DrawBlock { uint drawCommands[]; };
layout(set = kPassSet, binding = kDrawsBindingDrawCounts, std430) buffer DrawCountBlock { uint drawCounts[]; };  // [tile * kCasterKinds + kind]
layout(set = kPassSet, binding = kDrawsBindingTileStats, std430) buffer StatsBlock { CullTileStats tileStats[]; };
layout(set = kPassSet, binding = kCullBindingTiles, std430) readonly buffer CullTileBlock {
    CullTileListHeader tileList;  // its count; the dispatch is tileList.drawsDispatch
};
layout(push_constant) uniform CullConstantsBlock { CullConstants constants; };  // its listsPerBuffer

void main() {
    uint meshIndex = gl_GlobalInvocationID.x;
    uint tile = gl_WorkGroupID.y;
    uint meshCount = cull.meshCount;
    if (meshIndex >= meshCount || tile >= tileList.count) return;
    uint count = listCounts[tile * meshCount + meshIndex];
    if (count == 0u) return;
    CullMesh mesh = cullMeshes[meshIndex];
    uint kind = materials[mesh.materialIndex].shadowMode == kShadowModeOn ? 0u : 1u;
    uint list = tile * kCasterKinds + kind;
    uint slot = atomicAdd(drawCounts[list], 1u);
    uint base = (list * meshCount + slot) * 5u;
    drawCommands[base + 0u] = mesh.indexCount;
    drawCommands[base + 1u] = count;
    drawCommands[base + 2u] = mesh.firstIndex;
    drawCommands[base + 3u] = uint(mesh.vertexOffset);
    // Where the list starts in its buffer (the one the caster pass binds for this tile).
    drawCommands[base + 4u] = visibleListStart(tile, constants.listsPerBuffer, cull.instanceCount) + mesh.firstListSlot;
    atomicAdd(tileStats[tile].draws, 1u);
    atomicAdd(tileStats[tile].instances, count);
    atomicAdd(tileStats[tile].triangles, count * (mesh.indexCount / 3u));
}
