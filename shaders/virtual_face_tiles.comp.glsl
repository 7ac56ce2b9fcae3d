#version 460
// Spot and point light faces' virtual pages as the compute rasterizer's tiles (virtual_page_tiles.glsl):
// page (pageX, pageY) of mip m of face f (level m * faceCount + f) is the face's perspective projection
// cropped to the page's square of NDC (shadows/virtual_faces.h virtualFacePageClipFromWorld, operation for
// operation), culled by its frustum's planes (shadows/spot_culling.h clipFrustumPlanes).
#include "virtual_page_tiles.glsl"
#include "virtual_face_structs.h"

layout(set = kPassSet, binding = kPageDrawBindingFaces, std430) readonly buffer FaceBlock { VirtualFaceData faces[]; };

CullTile pageTile(VirtualPageDraw draw) {
    uint level = draw.entry / (constants.pagesPerSide * constants.pagesPerSide);
    uint mip = level / constants.faceCount, face = level % constants.faceCount;
    float pages = float(constants.pagesPerSide >> mip);  // the page is 2 / pages NDC wide
    mat4 crop = mat4(1.0);  // the page's NDC square to [-1, 1]; depth and w unchanged
    crop[0][0] = pages;
    crop[1][1] = pages;
    crop[3][0] = pages - 1.0 - 2.0 * float(draw.pageX);
    crop[3][1] = pages - 1.0 - 2.0 * float(draw.pageY);
    CullTile tile;
    tile.clipFromWorld = crop * faces[face].clipFromWorld;
    mat4 t = transpose(tile.clipFromWorld);  // rows (Gribb & Hartmann): left, right, bottom, top, far
    tile.planes[0] = t[3] + t[0];
    tile.planes[1] = t[3] - t[0];
    tile.planes[2] = t[3] + t[1];
    tile.planes[3] = t[3] - t[1];
    tile.planes[4] = t[3] - t[2];
    tile.lightFromWorld = mat4(1.0);
    tile.frustumMin = vec3(-uintBitsToFloat(0x7f7fffffu));  // the planes alone cull
    tile.kind = kCullTilePerspective;
    tile.frustumMax = vec3(uintBitsToFloat(0x7f7fffffu));
    tile.reserved0 = 0.0;
    tile.halfExtent = 0.0;
    tile.farDistance = 0.0;
    tile.cascadeIndex = 0.0;
    tile.blendCullingFactor = 0.0;
    tile.wsLightDirection = vec3(0.0);
    tile.slopeBias = constants.slopeBias;
    tile.receiverDepth = vec4(0.0);  // directional tiles' only
    tile.receiverSphere = vec4(0.0, 0.0, 0.0, -1.0);
    return tile;
}
