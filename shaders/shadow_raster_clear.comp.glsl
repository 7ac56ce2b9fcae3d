#version 460
// Compute rasterizer, pass 0 (shadow_raster.glsl): clears the tiles it will draw to depth 1 (the
// cached tiles keep last frame's depth), one thread per texel of each listed tile.
#include "shadow_raster.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    CullTile tile = cull.tiles[rasterTile(raster.firstRasterTile + gl_WorkGroupID.z)];
    uvec2 texel = uvec2(tile.viewport.xy) + gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(tile.viewport.zw)))) return;
    atlasDepth[texel.y * raster.atlasSize + texel.x] = floatBitsToUint(1.0);
}
