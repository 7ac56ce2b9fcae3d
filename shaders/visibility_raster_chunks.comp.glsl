#version 460
// Visibility rasterizer, pass 3 (visibility_raster.glsl): one workgroup per chunk of a large piece,
// one thread per pixel of the chunk.
#include "visibility_raster.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    uint chunk = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (chunk >= min(counters.chunksQueued, raster.chunkCapacity)) return;
    uvec2 entry = chunks[chunk];
    uint payload;
    RasterTriangleSetup t = unpackViewPiece(largePieces[entry.x], payload);
    ivec2 pixel = ivec2(entry.y & 0xffffu, entry.y >> 16) + ivec2(gl_LocalInvocationID.xy);
    if (pixel.x <= t.bounds.z && pixel.y <= t.bounds.w) rasterizePixel(t, payload, pixel.x, pixel.y);
}
