// The compute rasterizer of the main view's visibility buffer (visibility_structs.h):
// the forward pass's opaque and alpha-tested draws (mesh.vert + lit.frag's coverage and depth test)
// done in compute with raster_core.glsl's rules, so the nearest surface of every pixel is the one the
// hardware keeps.
// - each instance is tested against the camera frustum first (its world bounds, a workgroup at once);
// - back faces of single-sided materials are culled as the hardware's CullMode::Back with
//   counter-clockwise front faces: by the sign of det(x, y, w) of the clip-space vertices, which is
//   the window-space orientation for triangles in front of the camera and stays right for clipped ones;
// - triangles are clipped to the view's depth range (0 <= z <= w, reversed Z) and the guard band;
// - alpha-tested (MASK) materials sample their base colour at the perspective-correct uv with the
//   uv change to the next pixel as gradients and drop texels below the cutoff;
// - the pixel keeps the largest (depth bits << 32 | payload) by a 64-bit atomicMax.
#ifndef PENUMBRA_VISIBILITY_RASTER_GLSL
#define PENUMBRA_VISIBILITY_RASTER_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#define RASTER_MAX_CLIPPED 10
#define PENUMBRA_VIEW_RASTER
#include "pass_bindings.h"
#include "raster_mesh.glsl"
#include "visibility_structs.h"

layout(set = kPassSet, binding = kVisibilityRasterBindingVisibility, std430) buffer VisibilityBlock { uint64_t visibility[]; };

const uint kViewClipPlanes = kClipGuard | kClipDepthNear | kClipDepthFar;

uint viewWidth() { return raster.width; }
uint viewHeight() { return raster.height; }

// Whether a triangle of the material shows at all: front faces, and back faces of double-sided ones.
bool facesShown(RasterVertex v[3], bool doubleSided) {
    float det = determinant(mat3(v[0].clip.xyw, v[1].clip.xyw, v[2].clip.xyw));
    return det < 0.0 || (doubleSided && det > 0.0);
}

// lit.frag's alpha test (MASK materials): base colour alpha below the cutoff is discarded.
bool maskKeeps(RasterTriangleSetup t, vec3 weights, int x, int y) {
    // Derivatives of the pixel's 2 x 2 quad, as the hardware's implicit level in lit.frag takes them.
    return rasterBaseAlpha(t, weights, ivec2(x, y) & ~1) >= materials[t.materialIndex].alphaCutoff;
}

void rasterizePixel(RasterTriangleSetup t, uint payload, int x, int y) {
    ivec2 p = texelCentre(x, y);
    if (!insideEdge(t.p[1], t.p[2], p) || !insideEdge(t.p[2], t.p[0], p) || !insideEdge(t.p[0], t.p[1], p)) return;
    vec3 weights = planeWeights(t, x, y);
    if (t.alphaTested && !maskKeeps(t, weights, x, y)) return;
    float z = clamp(dot(weights, t.z), 0.0, 1.0);
    uint64_t word = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(payload);
    uint pixel = uint(y) * viewWidth() + uint(x);
    // A plain read first: most covered pixels already hold something nearer (the early depth test).
    if (word > visibility[pixel]) atomicMax(visibility[pixel], word);
}

void rasterizePiece(RasterTriangleSetup t, uint payload) {
    for (int y = t.bounds.y; y <= t.bounds.w; ++y)
        for (int x = t.bounds.x; x <= t.bounds.z; ++x) rasterizePixel(t, payload, x, y);
}

// A queued piece of the main view: packPiece's layout with the payload in point2.w (the alpha test
// follows from the material).
RasterPiece packViewPiece(RasterTriangleSetup t, uint payload) {
    RasterPiece piece = packPiece(t, 0.0);
    piece.point2.w = int(payload);
    return piece;
}
RasterTriangleSetup unpackViewPiece(RasterPiece piece, out uint payload) {
    RasterTriangleSetup t = unpackPiece(piece);
    payload = uint(piece.point2.w);
    t.alphaTested = materials[t.materialIndex].alphaMode == kAlphaMask;
    return t;
}

#endif
