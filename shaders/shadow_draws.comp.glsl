#version 460
// Compacts the (tile, mesh) lists of shadow_cull.comp into indirect draws (cull_structs.h): one
// invocation per (mesh, tile); a non-empty list becomes one VkDrawIndexedIndirectCommand drawing
// its instances, in the tile's opaque or alpha-tested list by the material's shadow mode
// (on, clip, dither; off casters are never listed), and counts into the tile's stats.
#include "pass_bindings.h"
#include "cull_structs.h"
#include "scene_structs.h"

layout(local_size_x = 64) in;

layout(set = 0, binding = kCullBindingFrame, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = 0, binding = kCullBindingMeshes, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = 0, binding = kCullBindingMaterials, std430) readonly buffer MaterialBlock { MaterialData materials[]; };
layout(set = 0, binding = kCullBindingListCounts, std430) readonly buffer ListCountBlock { uint listCounts[]; };
// [(tile * kCasterKinds + kind) * meshes + i] x 5 uints: indexCount, instanceCount, firstIndex,
// vertexOffset, firstInstance.
layout(set = 0, binding = kDrawsBindingDrawCommands, std430) writeonly buffer DrawBlock { uint drawCommands[]; };
layout(set = 0, binding = kDrawsBindingDrawCounts, std430) buffer DrawCountBlock { uint drawCounts[]; };  // [tile * kCasterKinds + kind]
layout(set = 0, binding = kDrawsBindingTileStats, std430) buffer StatsBlock { CullTileStats tileStats[]; };

void main() {
    uint meshIndex = gl_GlobalInvocationID.x;
    uint tile = gl_WorkGroupID.y;
    uint meshCount = cull.counts.z;
    if (meshIndex >= meshCount || tile >= cull.counts.x) return;
    uint count = listCounts[tile * meshCount + meshIndex];
    if (count == 0u) return;
    CullMesh mesh = cullMeshes[meshIndex];
    uint kind = materials[mesh.draw.w].flags.w == kShadowModeOn ? 0u : 1u;
    uint list = tile * kCasterKinds + kind;
    uint slot = atomicAdd(drawCounts[list], 1u);
    uint base = (list * meshCount + slot) * 5u;
    drawCommands[base + 0u] = mesh.draw.x;
    drawCommands[base + 1u] = count;
    drawCommands[base + 2u] = mesh.draw.y;
    drawCommands[base + 3u] = mesh.draw.z;
    drawCommands[base + 4u] = tile * cull.counts.y + mesh.counts.x;
    atomicAdd(tileStats[tile].counts.x, 1u);
    atomicAdd(tileStats[tile].counts.y, count);
    atomicAdd(tileStats[tile].counts.z, count * (mesh.draw.x / 3u));
}
