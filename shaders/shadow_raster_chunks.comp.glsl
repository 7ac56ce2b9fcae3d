#version 460
// Compute rasterizer, pass 3 (shadow_raster.glsl): one workgroup per chunk of a large piece, one
// thread per texel of the chunk.
#include "shadow_raster.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    uint chunk = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (chunk >= min(counters.chunksQueued, raster.chunkCapacity)) return;
    uvec2 entry = chunks[chunk];
    RasterPiece piece = largePieces[entry.x];
    RasterTriangleSetup t = unpackPiece(piece);
    float slopeBias = piece.inverseW.w;
    ivec2 texel = ivec2(entry.y & 0xffffu, entry.y >> 16) + ivec2(gl_LocalInvocationID.xy);
    if (texel.x >= t.bounds.x && texel.x <= t.bounds.z && texel.y >= t.bounds.y && texel.y <= t.bounds.w)
        rasterizeTexel(t, slopeBias, texel.x, texel.y);
}
