// The compute rasterizer of shadow depth (issue 10): what the hardware does for the shadow caster
// pass (shadow_caster.vert / .frag, depth clamp, no culling), done in compute so it runs on every SM.
// The same rules as Vulkan's rasterization, so both paths write the same depth:
// - triangles clipped to w > kNearW and to a guard band of kGuard viewports (as the hardware's own
//   clipping: coverage inside the viewport is unchanged), vertices to window coordinates with the
//   tile's viewport, snapped to 1/256 texel (8 sub-pixel bits, what NVIDIA and llvmpipe use);
// - coverage at texel centres by exact integer edge functions (32 x 32 -> 64-bit products) with the
//   top-left fill rule of a y-down framebuffer; both faces cast;
// - depth: window z interpolated linearly in window space (z/w for perspective tiles), plus the
//   tile's slope-scale bias times max(|dz/dx|, |dz/dy|), clamped to [0, 1] (pancaking, seed 000 §4.5);
// - alpha-tested casters (seed 000 §5.1-§5.3) sample their texture at the perspective-correct uv with
//   the uv change to the next texel in x and y as gradients: the LOD rule of shadow_caster.frag;
// - depth as float bits (all >= 0, so they order like the floats) into a buffer by atomicMin.
#ifndef PENUMBRA_SHADOW_RASTER_GLSL
#define PENUMBRA_SHADOW_RASTER_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#include "bindings.glsl"
#include "cull_structs.h"

layout(set = 0, binding = 5, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = 0, binding = 6, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = 0, binding = 7, std430) readonly buffer IndexBlock { uint indices[]; };
layout(set = 0, binding = 8, std430) buffer DepthBlock { uint atlasDepth[]; };  // atlasSize^2 float bits
layout(set = 0, binding = 9, std430) buffer CounterBlock { RasterCounters counters; };
layout(set = 0, binding = 10, std430) buffer LargeBlock { RasterPiece largePieces[]; };
layout(set = 0, binding = 11, std430) buffer ChunkBlock { uvec2 chunks[]; };  // (large piece, chunk x | y << 16)

layout(push_constant) uniform RasterConstants {
    uvec4 pass;      // x = first entry of CullFrame::rasterTiles for this atlas, y = their count, z = atlas size
    uvec4 capacity;  // x = large pieces, y = chunks the queues hold
} raster;

// Culling tile drawn by entry `i` of the frame's raster tile list.
uint rasterTile(uint i) { return cull.rasterTiles[i / 4u][i % 4u]; }

const float kNearW = 1e-5;
const float kGuard = 2.0;  // clip-space |x|, |y| <= kGuard w: window coordinates stay within 2^22 sub-texels
const float kSubpixel = 256.0;
const int kMaxClipped = 9;  // a triangle clipped by 5 planes has at most 8 vertices

struct RasterVertex {
    vec4 clip;
    vec2 uv;
};

// A triangle ready for coverage: snapped window positions (1/256 texel), window z, 1/w and uv/w.
struct RasterTriangleSetup {
    ivec2 p[3];
    vec3 z;
    vec3 invW;
    vec2 uvOverW[3];
    float area;          // twice the area in sub-texel units, > 0 (counter-clockwise in y-down window space)
    ivec4 bounds;        // texels x0, y0, x1, y1 (inclusive) inside the scissor
    vec2 depthSlope;     // dz per texel in x and y
    uint materialIndex;
    bool alphaTested;
};

RasterVertex casterVertex(uint vertexIndex, mat4 clipFromObject) {
    VertexData vertex = vertices[vertexIndex];
    RasterVertex v;
    v.clip = clipFromObject * vec4(vertex.osPositionU.xyz, 1.0);
    v.uv = vec2(vertex.osPositionU.w, vertex.osNormalV.w);
    return v;
}

// Exact sign of x1 * y1 - x2 * y2 for |values| < 2^23: -1, 0 or 1.
int crossSign(int x1, int y1, int x2, int y2) {
    int aHigh, aLow, bHigh, bLow;
    imulExtended(x1, y1, aHigh, aLow);
    imulExtended(x2, y2, bHigh, bLow);
    if (aHigh != bHigh) return aHigh > bHigh ? 1 : -1;
    uint a = uint(aLow), b = uint(bLow);
    return a == b ? 0 : (a > b ? 1 : -1);
}

// Sign of the edge function of edge a->b at p (> 0: p left of the edge in y-down window space).
int edgeSign(ivec2 a, ivec2 b, ivec2 p) { return crossSign(b.x - a.x, p.y - a.y, b.y - a.y, p.x - a.x); }
float edgeValue(ivec2 a, ivec2 b, ivec2 p) {
    return float(b.x - a.x) * float(p.y - a.y) - float(b.y - a.y) * float(p.x - a.x);
}

// Sets up the triangle (a, b, c) of `tile` (all with w > kNearW, inside the guard band); false when
// nothing of it can cover a texel.
bool setupTriangle(CullTile tile, RasterVertex a, RasterVertex b, RasterVertex c, out RasterTriangleSetup t) {
    RasterVertex v[3] = RasterVertex[3](a, b, c);
    vec2 minWindow = vec2(1e30), maxWindow = vec2(-1e30);
    for (int i = 0; i < 3; ++i) {
        float invW = 1.0 / v[i].clip.w;
        vec3 ndc = v[i].clip.xyz * invW;
        vec2 window = tile.viewport.xy + (ndc.xy * 0.5 + 0.5) * tile.viewport.zw;
        t.p[i] = ivec2(round(window * kSubpixel));
        t.z[i] = ndc.z;
        t.invW[i] = invW;
        t.uvOverW[i] = v[i].uv * invW;
        minWindow = min(minWindow, window);
        maxWindow = max(maxWindow, window);
    }
    int orientation = edgeSign(t.p[0], t.p[1], t.p[2]);
    if (orientation == 0) return false;
    if (orientation < 0) {  // both faces cast: make it counter-clockwise
        ivec2 p = t.p[1]; t.p[1] = t.p[2]; t.p[2] = p;
        float z = t.z[1]; t.z[1] = t.z[2]; t.z[2] = z;
        float w = t.invW[1]; t.invW[1] = t.invW[2]; t.invW[2] = w;
        vec2 uv = t.uvOverW[1]; t.uvOverW[1] = t.uvOverW[2]; t.uvOverW[2] = uv;
    }
    t.area = edgeValue(t.p[0], t.p[1], t.p[2]);
    // Texels whose centres may be covered, inside the scissor.
    ivec2 lo = ivec2(floor(minWindow - 0.5)), hi = ivec2(ceil(maxWindow - 0.5));
    lo = max(lo, ivec2(tile.scissor.xy));
    hi = min(hi, ivec2(tile.scissor.zw) - 1);
    t.bounds = ivec4(lo, hi);
    if (lo.x > hi.x || lo.y > hi.y) return false;
    // The plane of window z over window x, y (for the slope-scale bias).
    vec2 d1 = vec2(t.p[1] - t.p[0]) / kSubpixel, d2 = vec2(t.p[2] - t.p[0]) / kSubpixel;
    float det = d1.x * d2.y - d1.y * d2.x;
    float z1 = t.z[1] - t.z[0], z2 = t.z[2] - t.z[0];
    t.depthSlope = vec2(z1 * d2.y - z2 * d1.y, z2 * d1.x - z1 * d2.x) / det;
    return true;
}

// Vulkan's top-left rule in a y-down framebuffer for a counter-clockwise edge from->to.
bool topLeft(ivec2 from, ivec2 to) {
    ivec2 d = to - from;
    return d.y < 0 || (d.y == 0 && d.x > 0);
}

ivec2 texelCentre(int x, int y) { return ivec2(x * 256 + 128, y * 256 + 128); }

bool insideEdge(ivec2 a, ivec2 b, ivec2 p) {
    int s = edgeSign(a, b, p);
    return s > 0 || (s == 0 && topLeft(a, b));
}

// The barycentric weights at a texel centre, covered or not.
vec3 planeWeights(RasterTriangleSetup t, int x, int y) {
    ivec2 p = texelCentre(x, y);
    return vec3(edgeValue(t.p[1], t.p[2], p), edgeValue(t.p[2], t.p[0], p), edgeValue(t.p[0], t.p[1], p)) / t.area;
}

vec2 perspectiveUv(RasterTriangleSetup t, vec3 weights) {
    float invW = dot(weights, t.invW);
    return (weights.x * t.uvOverW[0] + weights.y * t.uvOverW[1] + weights.z * t.uvOverW[2]) / invW;
}

// seed 000 §5.1-§5.3 as shadow_caster.frag: clip below the cutoff, dither by interleaved gradient noise.
bool alphaKeeps(RasterTriangleSetup t, vec3 weights, int x, int y) {
    MaterialData material = materials[t.materialIndex];
    float alpha = material.baseColorFactor.a;
    if (material.flags.x != 0u) {
        vec2 uv = perspectiveUv(t, weights);
        vec2 dx = perspectiveUv(t, planeWeights(t, x + 1, y)) - uv;
        vec2 dy = perspectiveUv(t, planeWeights(t, x, y + 1)) - uv;
        // Every thread of a workgroup rasterizes the same instance (pass 1) or triangle (pass 3), so the
        // texture index is uniform; broadcasting it says so to the compiler.
        uint texture = subgroupBroadcastFirst(material.flags.x - 1u);
        alpha *= textureLod(baseColorTextures[texture], uv, textureLevel(texture, dx, dy)).a;
    }
    if (material.flags.w == kShadowModeClip && alpha < material.params.z) return false;
    if (material.flags.w == kShadowModeDither && alpha < interleavedGradientNoise(vec2(x, y) + 0.5)) return false;
    return true;
}

void rasterizeTexel(RasterTriangleSetup t, float slopeBias, int x, int y) {
    ivec2 p = texelCentre(x, y);
    if (!insideEdge(t.p[1], t.p[2], p) || !insideEdge(t.p[2], t.p[0], p) || !insideEdge(t.p[0], t.p[1], p)) return;
    vec3 weights = planeWeights(t, x, y);
    if (t.alphaTested && !alphaKeeps(t, weights, x, y)) return;
    float z = dot(weights, t.z) + slopeBias * max(abs(t.depthSlope.x), abs(t.depthSlope.y));
    z = clamp(z, 0.0, 1.0);
    // A plain read first: far-away casters put thousands of triangles on one texel, and most of them
    // lie behind what is there already (the early depth test of the hardware path).
    uint texel = uint(y) * raster.pass.z + uint(x), bits = floatBitsToUint(z);
    if (bits < atlasDepth[texel]) atomicMin(atlasDepth[texel], bits);
}

bool isAlphaTested(CullMesh mesh) { return materials[mesh.draw.w].flags.w != kShadowModeOn; }

// Distance of a clip-space vertex to clip plane `plane` (>= 0 inside): w > kNearW, |x|, |y| <= kGuard w.
float planeDistance(vec4 clip, int plane) {
    if (plane == 0) return clip.w - kNearW;
    float g = kGuard * clip.w;
    if (plane == 1) return g - clip.x;
    if (plane == 2) return g + clip.x;
    if (plane == 3) return g - clip.y;
    return g + clip.y;
}

// Clips the triangle (Sutherland-Hodgman against the 5 planes) into a fan; returns its vertex count.
int clipTriangle(RasterVertex v[3], out RasterVertex polygon[kMaxClipped]) {
    polygon[0] = v[0]; polygon[1] = v[1]; polygon[2] = v[2];
    int count = 3;
    for (int plane = 0; plane < 5; ++plane) {
        bool allInside = true;
        for (int i = 0; i < count; ++i) allInside = allInside && planeDistance(polygon[i].clip, plane) >= 0.0;
        if (allInside) continue;
        RasterVertex clipped[kMaxClipped];
        int kept = 0;
        for (int i = 0; i < count; ++i) {
            RasterVertex a = polygon[i], b = polygon[(i + 1) % count];
            float da = planeDistance(a.clip, plane), db = planeDistance(b.clip, plane);
            if (da >= 0.0) clipped[kept++] = a;
            if ((da >= 0.0) != (db >= 0.0) && kept < kMaxClipped) {
                float s = da / (da - db);
                clipped[kept].clip = mix(a.clip, b.clip, s);
                clipped[kept].uv = mix(a.uv, b.uv, s);
                ++kept;
            }
        }
        count = kept;
        for (int i = 0; i < count; ++i) polygon[i] = clipped[i];
        if (count < 3) return 0;
    }
    return count;
}

// Fetches triangle `triangle` of `mesh` in the tile's clip space (clipFromObject = the tile's
// clipFromWorld x the instance's worldFromObject).
void fetchTriangle(CullMesh mesh, uint triangle, mat4 clipFromObject, out RasterVertex v[3]) {
    for (int i = 0; i < 3; ++i) {
        uint index = indices[mesh.draw.y + triangle * 3u + uint(i)];
        v[i] = casterVertex(uint(int(index) + int(mesh.draw.z)), clipFromObject);
    }
}

// Whether some vertex lies outside w > kNearW or the guard band (the rare case that clips).
bool needsClipping(RasterVertex v[3]) {
    for (int i = 0; i < 3; ++i)
        for (int plane = 0; plane < 5; ++plane)
            if (planeDistance(v[i].clip, plane) < 0.0) return true;
    return false;
}

RasterPiece packPiece(RasterTriangleSetup t, float slopeBias) {
    RasterPiece piece;
    piece.points01 = ivec4(t.p[0], t.p[1]);
    piece.point2 = ivec4(t.p[2], int(t.materialIndex), t.alphaTested ? 1 : 0);
    piece.depth = vec4(t.z, t.area);
    piece.inverseW = vec4(t.invW, slopeBias);
    piece.uvOverW01 = vec4(t.uvOverW[0], t.uvOverW[1]);
    piece.uvOverW2Slope = vec4(t.uvOverW[2], t.depthSlope);
    piece.bounds = t.bounds;
    return piece;
}

RasterTriangleSetup unpackPiece(RasterPiece piece) {
    RasterTriangleSetup t;
    t.p[0] = piece.points01.xy;
    t.p[1] = piece.points01.zw;
    t.p[2] = piece.point2.xy;
    t.materialIndex = uint(piece.point2.z);
    t.alphaTested = piece.point2.w != 0;
    t.z = piece.depth.xyz;
    t.area = piece.depth.w;
    t.invW = piece.inverseW.xyz;
    t.uvOverW[0] = piece.uvOverW01.xy;
    t.uvOverW[1] = piece.uvOverW01.zw;
    t.uvOverW[2] = piece.uvOverW2Slope.xy;
    t.depthSlope = piece.uvOverW2Slope.zw;
    t.bounds = piece.bounds;
    return t;
}

uint boundsArea(ivec4 bounds) { return uint(bounds.z - bounds.x + 1) * uint(bounds.w - bounds.y + 1); }

#endif
