#version 460
// Compute rasterizer, pass 0 (shadow_raster.glsl): clears the tiles it will draw to depth 1 (the
// cached tiles keep last frame's depth), one thread per texel of each entry of the raster list
// (rasterList.clearDispatch: z = the entry).
#include "shadow_raster.glsl"

layout(local_size_x = kRasterClearGroup, local_size_y = kRasterClearGroup) in;

void main() {
    uint tileIndex;
    if (!rasterTile(gl_WorkGroupID.z, tileIndex)) return;
    CullTile tile = tiles[tileIndex];
    uvec2 texel = uvec2(tile.viewport.xy) + gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(tile.viewport.zw)))) return;
    atlasDepth[texel.y * raster.depthSide + texel.x] = floatBitsToUint(1.0);
}
