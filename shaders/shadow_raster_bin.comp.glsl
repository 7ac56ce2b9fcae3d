#version 460
// Compute rasterizer, pass 2 (shadow_raster.glsl): one workgroup per queued large piece splits its
// texel bounds into kRasterChunk x kRasterChunk chunks for pass 3, keeping those the piece overlaps.
#include "shadow_raster.glsl"

layout(local_size_x = 64) in;

shared uint chunkCount, chunksWide;
shared ivec2 chunkOrigin;

// Whether the piece can cover a texel centre of the chunk: no edge has all four corner centres outside.
bool overlapsChunk(RasterTriangleSetup t, ivec2 origin) {
    ivec2 corners[4] = ivec2[4](texelCentre(origin.x, origin.y), texelCentre(origin.x + int(kRasterChunk) - 1, origin.y),
                                texelCentre(origin.x, origin.y + int(kRasterChunk) - 1),
                                texelCentre(origin.x + int(kRasterChunk) - 1, origin.y + int(kRasterChunk) - 1));
    for (int e = 0; e < 3; ++e) {
        ivec2 a = t.p[e], b = t.p[(e + 1) % 3];
        bool allOutside = true;
        for (int c = 0; c < 4; ++c) allOutside = allOutside && edgeSign(a, b, corners[c]) < 0;
        if (allOutside) return false;
    }
    return true;
}

void main() {
    uint large = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (large >= min(counters.counts.x, raster.capacity.x)) return;
    RasterTriangleSetup t = unpackPiece(largePieces[large]);
    if (gl_LocalInvocationID.x == 0u) {
        chunkOrigin = t.bounds.xy;
        chunksWide = uint(t.bounds.z - t.bounds.x) / kRasterChunk + 1u;
        chunkCount = chunksWide * (uint(t.bounds.w - t.bounds.y) / kRasterChunk + 1u);
    }
    barrier();
    for (uint i = gl_LocalInvocationID.x; i < chunkCount; i += 64u) {
        uvec2 origin = uvec2(chunkOrigin) + uvec2(i % chunksWide, i / chunksWide) * kRasterChunk;
        if (!overlapsChunk(t, ivec2(origin))) continue;
        uint slot = atomicAdd(counters.counts.y, 1u);
        if (slot < raster.capacity.y) chunks[slot] = uvec2(large, origin.x | (origin.y << 16));
        else atomicAdd(counters.counts.w, 1u);
    }
}
