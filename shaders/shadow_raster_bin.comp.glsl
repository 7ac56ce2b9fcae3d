#version 460
// Compute rasterizer, pass 2 (shadow_raster.glsl): one workgroup per queued large piece splits its
// texel bounds into kRasterChunk x kRasterChunk chunks for pass 3, keeping those the piece overlaps.
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

shared uint chunkCount, chunksWide;
shared ivec2 chunkOrigin;

void main() {
    uint large = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (large >= min(counters.largeQueued, raster.largeCapacity)) return;
    RasterTriangleSetup t = unpackPiece(largePieces[large]);
    if (gl_LocalInvocationID.x == 0u) {
        chunkOrigin = t.bounds.xy;
        chunksWide = uint(t.bounds.z - t.bounds.x) / kRasterChunk + 1u;
        chunkCount = chunksWide * (uint(t.bounds.w - t.bounds.y) / kRasterChunk + 1u);
    }
    barrier();
    for (uint i = gl_LocalInvocationID.x; i < chunkCount; i += 64u) {
        uvec2 origin = uvec2(chunkOrigin) + uvec2(i % chunksWide, i / chunksWide) * kRasterChunk;
        if (!overlapsChunk(t, ivec2(origin), int(kRasterChunk))) continue;
        uint slot = atomicAdd(counters.chunksQueued, 1u);
        if (slot < raster.chunkCapacity) chunks[slot] = uvec2(large, origin.x | (origin.y << 16));
        else atomicAdd(counters.chunksDropped, 1u);
    }
}
