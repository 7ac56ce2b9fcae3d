#version 460
// Compute rasterizer, pass 3 (shadow_raster.glsl): one workgroup per chunk of a large triangle, one
// thread per texel of the chunk; the first thread sets the triangle up for all.
#include "shadow_raster.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

shared RasterTriangleSetup sharedPieces[6];
shared int sharedCount;
shared float sharedSlopeBias;

void main() {
    uint chunk = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    if (chunk >= min(counters.counts.y, kRasterMaxChunks)) return;  // uniform over the workgroup
    uvec2 entry = chunks[chunk];
    if (gl_LocalInvocationIndex == 0u) {
        uvec4 ids = largeTriangles[entry.x].ids;
        CullTile tile = cull.tiles[ids.x];
        RasterTriangleSetup pieces[6];
        sharedCount = setupPieces(tile, ids.w, ids.y, ids.z, pieces);
        for (int i = 0; i < sharedCount; ++i) sharedPieces[i] = pieces[i];
        sharedSlopeBias = tile.wsLightDirection.w;
    }
    barrier();
    ivec2 texel = ivec2(entry.y & 0xffffu, entry.y >> 16) + ivec2(gl_LocalInvocationID.xy);
    for (int i = 0; i < sharedCount; ++i) {
        ivec4 b = sharedPieces[i].bounds;
        if (texel.x >= b.x && texel.x <= b.z && texel.y >= b.y && texel.y <= b.w)
            rasterizeTexel(sharedPieces[i], sharedSlopeBias, texel.x, texel.y);
    }
}
