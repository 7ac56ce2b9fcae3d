// Whether a compute rasterizer may skip a whole meshlet (render.meshletCulling;
// cull_structs.h Meshlet): its box lies outside the view or shadow tile, or every triangle of it faces
// away from the camera. Both tests are conservative: a skipped meshlet would have drawn nothing.
// Written in the common subset of GLSL and C++ (glm), like tone_mapping.glsl: the rasterizers include
// it and tests/unit/meshlet_culling_test.cpp checks the very same functions against every triangle.
#ifndef PENUMBRA_MESHLET_CULLING_GLSL
#define PENUMBRA_MESHLET_CULLING_GLSL
#include "cull_structs.h"

#ifdef __cplusplus
namespace penumbra::gpu_data::meshlet_culling {
using namespace glm;
#endif

// The sides of a clip volume a box is tested against (bit masks): x and y within [-w, w] (what the
// viewport covers: a rasterizer writes no pixel outside it), w above kMeshletNearW (perspective
// shadow tiles clip there), and the main view's reversed-Z depth range 0 <= z <= w.
const uint kMeshletSidesXY = 15u, kMeshletSideNearW = 16u, kMeshletSidesDepth = 96u;
const float kMeshletNearW = 1e-5f;
// Relative slack of both tests, so that rounding in the box's corners or the cone never skips a
// meshlet that touches the boundary.
const float kMeshletSlack = 1e-4f;

// The sides of `sides` that clip-space point `c` lies beyond.
PENUMBRA_INLINE uint meshletOutcode(vec4 c, uint sides) {
    float slack = kMeshletSlack * abs(c.w);
    uint code = 0u;
    if (c.x < -c.w - slack) code |= 1u;
    if (c.x > c.w + slack) code |= 2u;
    if (c.y < -c.w - slack) code |= 4u;
    if (c.y > c.w + slack) code |= 8u;
    if (c.w < kMeshletNearW) code |= 16u;
    if (c.z < -slack) code |= 32u;
    if (c.z > c.w + slack) code |= 64u;
    return code & sides;
}

// Whether the object-space box [osMin, osMax] lies wholly beyond one side of `sides` of the clip
// volume of clipFromObject (then so does every triangle inside it).
PENUMBRA_INLINE bool meshletBoxOutside(mat4 clipFromObject, vec3 osMin, vec3 osMax, uint sides) {
    uint outside = sides;
    for (int i = 0; i < 8; ++i) {
        vec3 corner = vec3((i & 1) != 0 ? osMax.x : osMin.x, (i & 2) != 0 ? osMax.y : osMin.y, (i & 4) != 0 ? osMax.z : osMin.z);
        outside &= meshletOutcode(clipFromObject * vec4(corner, 1.0f), sides);
    }
    return outside != 0u;
}

// Whether no triangle of the box can cover a texel of a viewport (x, y, width, height in texels): the
// box's window-space bounds hold no texel centre along x or along y (a triangle covers a texel only when
// its centre lies inside it, so within its vertices' bounds). The bounds are widened by a rasterizer's
// vertex snapping (half of 1/256 texel, rounded up) and kMeshletSlack of their size. False when a corner
// lies at or behind w = kMeshletNearW (perspective: no bounds). What a far cascade or a coarse virtual
// page sees of small meshes: meshlets smaller than a texel, between its centres.
PENUMBRA_INLINE bool meshletBetweenTexelCentres(mat4 clipFromObject, vec3 osMin, vec3 osMax, vec4 viewport) {
    vec2 lo = vec2(1e30f), hi = vec2(-1e30f);
    for (int i = 0; i < 8; ++i) {
        vec3 corner = vec3((i & 1) != 0 ? osMax.x : osMin.x, (i & 2) != 0 ? osMax.y : osMin.y, (i & 4) != 0 ? osMax.z : osMin.z);
        vec4 c = clipFromObject * vec4(corner, 1.0f);
        if (c.w <= kMeshletNearW) return false;
        vec2 window = vec2(viewport.x, viewport.y) + (vec2(c.x, c.y) / c.w * 0.5f + 0.5f) * vec2(viewport.z, viewport.w);
        lo = min(lo, window);
        hi = max(hi, window);
    }
    vec2 margin = vec2(1.0f / 256.0f) + kMeshletSlack * (hi - lo + vec2(1.0f));
    lo -= margin;
    hi += margin;
    // A centre i + 0.5 in [lo, hi] exists when ceil(lo - 0.5) <= floor(hi - 0.5).
    return ceil(lo.x - 0.5f) > floor(hi.x - 0.5f) || ceil(lo.y - 0.5f) > floor(hi.y - 0.5f);
}
// The camera's position in an instance's object space (worldFromObject affine and invertible).
PENUMBRA_INLINE vec3 meshletObjectEye(mat4 worldFromObject, vec3 wsEye) {
    return inverse(mat3(worldFromObject)) * (wsEye - vec3(worldFromObject[3]));
}

// Whether every triangle of a meshlet faces away from an eye at osEye (object space): meshoptimizer's
// cone test, dot(normalize(apex - eye), axis) >= cutoff. A triangle's facing is the sign of
// dot(p - eye, n), which an affine transform keeps (times the sign of its determinant), so the test in
// object space is the test in the world for instances that are not mirrored (the caller checks).
PENUMBRA_INLINE bool meshletFacesAway(vec3 coneApex, vec3 coneAxis, float coneCutoff, vec3 osEye) {
    float cutoff = coneCutoff + kMeshletSlack;
    if (cutoff >= 1.0f) return false;
    vec3 d = coneApex - osEye;
    return dot(d, coneAxis) >= cutoff * length(d);
}

#ifdef __cplusplus
}  // namespace penumbra::gpu_data::meshlet_culling
#endif
#endif
