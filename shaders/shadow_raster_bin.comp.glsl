#version 460
// Compute rasterizer, pass 2 (shadow_raster.glsl): one workgroup per queued large triangle splits
// its texel bounds into kRasterChunk x kRasterChunk chunks for pass 3.
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

shared uint firstChunk, chunkCount, chunksWide;
shared ivec2 chunkOrigin;

void main() {
    uint large = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (large >= min(counters.counts.x, kRasterMaxLarge)) return;
    if (gl_LocalInvocationID.x == 0u) {
        uvec4 ids = largeTriangles[large].ids;
        RasterTriangleSetup pieces[6];
        int count = setupPieces(cull.tiles[ids.x], ids.w, ids.y, ids.z, pieces);
        ivec4 bounds = ivec4(1 << 30, 1 << 30, -(1 << 30), -(1 << 30));
        for (int i = 0; i < count; ++i) bounds = ivec4(min(bounds.xy, pieces[i].bounds.xy), max(bounds.zw, pieces[i].bounds.zw));
        chunkCount = 0u;
        if (count > 0) {
            chunkOrigin = bounds.xy;
            chunksWide = uint(bounds.z - bounds.x) / kRasterChunk + 1u;
            uint chunksHigh = uint(bounds.w - bounds.y) / kRasterChunk + 1u;
            chunkCount = chunksWide * chunksHigh;
            firstChunk = atomicAdd(counters.counts.y, chunkCount);
            if (firstChunk + chunkCount > kRasterMaxChunks) {
                atomicAdd(counters.counts.w, chunkCount);
                chunkCount = firstChunk < kRasterMaxChunks ? kRasterMaxChunks - firstChunk : 0u;
            }
        }
    }
    barrier();
    for (uint i = gl_LocalInvocationID.x; i < chunkCount; i += 64u) {
        uvec2 origin = uvec2(chunkOrigin) + uvec2(i % chunksWide, i / chunksWide) * kRasterChunk;
        chunks[firstChunk + i] = uvec2(large, origin.x | (origin.y << 16));
    }
}
