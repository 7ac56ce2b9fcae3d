#version 460
// Compute rasterizer, pass 1 (shadow_raster.glsl): one workgroup per work item (RasterWorkItem, queued
// by shadow_raster_expand.comp): up to kRasterMeshletsPerItem meshlets of one instance in one tile, or
// a packed item, up to kRasterPackTriangles / T instances of a one-meshlet mesh of T triangles (a box's
// 12: 21 instances, so a million small objects are not a million workgroups of 12 busy threads). Its
// threads take the triangles 64 at a time; a meshlet whose box lies outside the tile is skipped whole
// (render.meshletCulling). Each thread sets up its triangle; by the texels its bounds cover it is:
// - small (<= kShadowSmallArea): rasterized by the thread;
// - medium (<= kShadowMediumArea): kept set up in shared memory; after the 64 triangles the workgroup
//   rasterizes the kept pieces together, one thread per block of kShadowBlock^2 texels, a block that
//   lies outside an edge rejected by its corners (binned in the workgroup: no queue, no dispatch);
// - large: queued, set up, for the chunk passes (shadow_raster_bin.comp, shadow_raster_chunks.comp).
// Both walk their texels with edge functions stepped in 32-bit integers where they are exact.
// Hierarchical rasterization as in Abrash's "Rasterization on Larrabee" and the software rasterizers
// of Nanite-style renderers: each triangle goes to the level whose unit of work fits its size.
#include "pass_bindings.h"
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kShadowRasterBindingWork, std430) readonly buffer WorkBlock { RasterWorkItem work[]; };

const uint kMediumSlots = 64u;

shared mat4 itemClipFromObject;  // a meshlet item's instance
shared bool meshletSkipped;
// The medium pieces of this round: count << 24 | blocks so far, one atomic giving a slot and its first block.
shared uint mediumCursor;
shared RasterTriangleSetup mediumPieces[kMediumSlots];
shared uint mediumEnd[kMediumSlots];  // one past each piece's last block in the round's sequence of blocks

void queueLarge(RasterTriangleSetup t, float slopeBias) {
    uint queued = atomicAdd(counters.largeQueued, 1u);
    if (queued < raster.largeCapacity) largePieces[queued] = packPiece(t, slopeBias);
    else atomicAdd(counters.largeDropped, 1u);
}

uint blocksWide(ivec4 bounds) { return uint(bounds.z - bounds.x) / uint(kShadowBlock) + 1u; }
uint blockCount(ivec4 bounds) { return blocksWide(bounds) * (uint(bounds.w - bounds.y) / uint(kShadowBlock) + 1u); }

// Rasterizes a small piece at once; keeps a medium one for the workgroup; queues a large one.
void rasterizeOrQueue(RasterTriangleSetup t, CullMesh mesh, float slopeBias) {
    t.materialIndex = mesh.materialIndex;
    t.alphaTested = isAlphaTested(mesh);
    uint area = boundsArea(t.bounds);
    if (area <= kShadowSmallArea) {
        rasterizeRect(t, slopeBias, t.bounds);
        return;
    }
    if (area <= kShadowMediumArea) {
        uint blocks = blockCount(t.bounds), cursor = atomicAdd(mediumCursor, (1u << 24) | blocks), slot = cursor >> 24;
        if (slot < kMediumSlots) {
            mediumPieces[slot] = t;
            mediumEnd[slot] = (cursor & 0xffffffu) + blocks;
            return;
        }
    }
    queueLarge(t, slopeBias);  // large, or a round with more medium pieces than slots (clipped fans)
}

// The round's medium pieces, one thread per kShadowBlock^2 block of their bounds. Called by every thread.
void rasterizeMediumPieces(float slopeBias) {
    barrier();  // the pieces are in shared memory
    uint pieces = min(mediumCursor >> 24, kMediumSlots);
    uint blocks = pieces > 0u ? mediumEnd[pieces - 1u] : 0u;
    if (gl_LocalInvocationID.x == 0u && pieces > 0u) atomicAdd(counters.mediumQueued, pieces);
    for (uint i = gl_LocalInvocationID.x; i < blocks; i += 64u) {
        uint lo = 0u, hi = pieces - 1u;  // the first piece whose end lies past block i
        while (lo < hi) {
            uint mid = (lo + hi) / 2u;
            if (mediumEnd[mid] > i) hi = mid;
            else lo = mid + 1u;
        }
        RasterTriangleSetup t = mediumPieces[lo];
        uint local = i - (lo > 0u ? mediumEnd[lo - 1u] : 0u), wide = blocksWide(t.bounds);
        ivec2 origin = t.bounds.xy + ivec2(local % wide, local / wide) * kShadowBlock;
        ivec4 block = ivec4(origin, min(origin + kShadowBlock - 1, t.bounds.zw));
        if (!edgesFitInt32(t) || !rectOutside(t, block)) rasterizeRect(t, slopeBias, block);
    }
    barrier();  // every thread done with the pieces
    if (gl_LocalInvocationID.x == 0u) mediumCursor = 0u;
    barrier();
}

void rasterizeTriangle(CullMesh mesh, uint triangle, mat4 clipFromObject, CullTile tile) {
    RasterVertex v[3];
    fetchTriangle(mesh, triangle, clipFromObject, v);
    RasterTriangleSetup t;
    if (!needsClipping(v, kShadowClipPlanes)) {  // nearly always: no polygon array, nothing in local memory
        if (setupTriangle(tile.viewport, tile.scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh, tile.slopeBias);
        return;
    }
    RasterVertex polygon[kMaxClipped];
    int vertexCount = clipTriangle(v, kShadowClipPlanes, polygon);
    for (int i = 1; i + 1 < vertexCount; ++i)
        if (setupTriangle(tile.viewport, tile.scissor, polygon[0], polygon[i], polygon[i + 1], t))
            rasterizeOrQueue(t, mesh, tile.slopeBias);
}

void rasterizeMeshlet(CullMesh mesh, Meshlet meshlet, CullTile tile) {
    uint lastTriangle = meshlet.firstTriangle + meshlet.triangleCount;
    for (uint round = meshlet.firstTriangle; round < lastTriangle; round += 64u) {  // uniform: barriers inside
        uint triangle = round + gl_LocalInvocationID.x;
        if (triangle < lastTriangle) rasterizeTriangle(mesh, triangle, itemClipFromObject, tile);
        rasterizeMediumPieces(tile.slopeBias);
    }
}

// A packed item: `count` instances from list slot item.instance of the tile's list, each the mesh's one meshlet.
void rasterizePacked(RasterWorkItem item, CullMesh mesh, CullTile tile) {
    Meshlet meshlet = meshlets[mesh.firstMeshlet];
    uint count = item.firstMeshlet & ~kRasterPackedItem, triangles = meshlet.triangleCount, total = count * triangles;
    uint listBuffer = visibleListBuffer(item.tile, raster.listsPerBuffer);
    uint listStart = visibleListStart(item.tile, raster.listsPerBuffer, cull.instanceCount) + item.instance;
    barrier();  // mediumCursor cleared
    for (uint round = 0u; round < total; round += 64u) {
        uint i = round + gl_LocalInvocationID.x;
        if (i < total) {  // each thread its instance's matrix: in shared memory they cost more than they save
            uint instance = visibleLists[listBuffer].entries[listStart + i / triangles];
            mat4 clipFromInstance = tile.clipFromWorld * instanceWorldFromObject(instances[instance]);
            rasterizeTriangle(mesh, meshlet.firstTriangle + i % triangles, clipFromInstance, tile);
        }
        rasterizeMediumPieces(tile.slopeBias);
    }
}

void main() {
    uint itemIndex = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (itemIndex >= min(counters.workQueued, raster.workCapacity)) return;  // past the last item (workDispatch)
    RasterWorkItem item = work[itemIndex];
    CullMesh mesh = cullMeshes[item.meshSlot];
    CullTile tile = tiles[item.tile];
    if (gl_LocalInvocationID.x == 0u) mediumCursor = 0u;
    if ((item.firstMeshlet & kRasterPackedItem) != 0u) {  // uniform: the workgroup's item
        rasterizePacked(item, mesh, tile);
        return;
    }
    if (gl_LocalInvocationID.x == 0u) itemClipFromObject = tile.clipFromWorld * instanceWorldFromObject(instances[item.instance]);
    uvec2 level = lodMeshlets(item.meshSlot, item.firstMeshlet >> kRasterLodShift);  // first, count
    uint firstMeshlet = item.firstMeshlet & kRasterMeshletMask;
    uint lastMeshlet = min(firstMeshlet + kRasterMeshletsPerItem, level.y);
    for (uint m = firstMeshlet; m < lastMeshlet; ++m) {
        Meshlet meshlet = meshlets[level.x + m];
        barrier();  // itemClipFromObject written; the last meshlet's threads done with meshletSkipped
        if (gl_LocalInvocationID.x == 0u) {
            // Depth is clamped, not clipped (pancaking): only the tile's sides and a perspective tile's near w.
            // Or, smaller than a texel, it lies between the texel centres (a far cascade's or coarse page's
            // view of small meshes): it covers no texel.
            meshletSkipped = raster.meshletCulling != 0u &&
                             (meshletBoxOutside(itemClipFromObject, meshlet.osMin.xyz, meshlet.osMax.xyz,
                                                kMeshletSidesXY | kMeshletSideNearW) ||
                              meshletBetweenTexelCentres(itemClipFromObject, meshlet.osMin.xyz, meshlet.osMax.xyz, tile.viewport));
            if (meshletSkipped) atomicAdd(counters.meshletsOutside, 1u);
        }
        barrier();
        if (!meshletSkipped) rasterizeMeshlet(mesh, meshlet, tile);
    }
}
