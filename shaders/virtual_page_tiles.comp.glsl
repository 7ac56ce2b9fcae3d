#version 460
// A directional light's virtual shadow map pages as the compute rasterizer's tiles (virtual_page_tiles.glsl):
// each page's orthographic projection and its square for the culling test.
#include "virtual_page_tiles.glsl"

CullTile pageTile(VirtualPageDraw draw) {
    uint level = draw.entry / (constants.pagesPerSide * constants.pagesPerSide);
    float lsPage = constants.firstLevelSize * exp2(float(level)) / float(constants.pagesPerSide);
    vec2 lsMin = vec2(draw.pageX, draw.pageY) * lsPage;
    float near = constants.lsDepthNear, far = constants.lsDepthFar;
    mat4 clipFromLight = mat4(vec4(2.0 / lsPage, 0.0, 0.0, 0.0), vec4(0.0, 2.0 / lsPage, 0.0, 0.0),
                              vec4(0.0, 0.0, -1.0 / (near - far), 0.0),
                              vec4(-2.0 * vec2(draw.pageX, draw.pageY) - 1.0, near / (near - far), 1.0));
    mat4 rotation = constants.lightRotationFromWorld;
    CullTile tile;
    // Culling as a directional tile centred on the page: its square, every depth, no blend culling.
    tile.lightFromWorld = rotation;
    tile.lightFromWorld[3] = vec4(-(lsMin + 0.5 * lsPage), 0.0, 1.0);
    for (int i = 0; i < 5; ++i) tile.planes[i] = vec4(0.0);
    tile.frustumMin = vec3(0.0);
    tile.kind = kCullTileDirectional;
    tile.frustumMax = vec3(0.0);
    tile.reserved0 = 0.0;
    tile.halfExtent = 0.5 * lsPage;
    tile.farDistance = uintBitsToFloat(0x7f7fffffu);  // the largest float: no depth culling
    tile.cascadeIndex = 0.0;
    tile.blendCullingFactor = 0.0;
    tile.wsLightDirection = -vec3(rotation[0][2], rotation[1][2], rotation[2][2]);
    tile.slopeBias = constants.slopeBias;
    tile.clipFromWorld = clipFromLight * rotation;
    tile.receiverDepth = vec4(0.0);  // no receiver culling: the page was asked for by what the view shows
    tile.receiverSphere = vec4(0.0, 0.0, 0.0, -1.0);
    return tile;
}
