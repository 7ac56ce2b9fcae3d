#version 460
// Visibility rasterizer, pass 2 (visibility_raster.glsl): one workgroup per queued large piece splits
// its pixel bounds into kRasterChunk x kRasterChunk chunks for pass 3, keeping those the piece
// overlaps; a chunk that finds the queue full is rasterized by its thread here.
#include "visibility_raster.glsl"

layout(local_size_x = 64) in;

shared uint chunkCount, chunksWide;

void main() {
    uint large = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (large >= min(counters.largeQueued, raster.largeCapacity)) return;
    uint payload;
    RasterTriangleSetup t = unpackViewPiece(largePieces[large], payload);
    if (gl_LocalInvocationID.x == 0u) {
        chunksWide = uint(t.bounds.z - t.bounds.x) / kRasterChunk + 1u;
        chunkCount = chunksWide * (uint(t.bounds.w - t.bounds.y) / kRasterChunk + 1u);
    }
    barrier();
    for (uint i = gl_LocalInvocationID.x; i < chunkCount; i += 64u) {
        ivec2 origin = t.bounds.xy + ivec2(i % chunksWide, i / chunksWide) * int(kRasterChunk);
        if (!overlapsChunk(t, origin, int(kRasterChunk))) continue;
        uint slot = atomicAdd(counters.chunksQueued, 1u);
        if (slot < raster.chunkCapacity) {
            chunks[slot] = uvec2(large, uint(origin.x) | (uint(origin.y) << 16));
            continue;
        }
        atomicAdd(counters.chunksDropped, 1u);  // full: this thread draws the chunk
        ivec2 last = min(origin + int(kRasterChunk) - 1, t.bounds.zw);
        for (int y = origin.y; y <= last.y; ++y)
            for (int x = origin.x; x <= last.x; ++x) rasterizePixel(t, payload, x, y);
    }
}
