// The geometry of the compute rasterizers (shadow_raster.glsl for the shadow atlases,
// visibility_raster.glsl for the main view): Vulkan's rasterization rules, so both give what the
// hardware gives.
// - triangles clipped to the planes a pass names (w > kNearW or the view's depth range, and a guard
//   band of kGuard viewports, as the hardware's own clipping: coverage inside the viewport is unchanged),
//   vertices to window coordinates, snapped to 1/256 pixel (8 sub-pixel bits, what NVIDIA and llvmpipe use);
// - coverage at pixel centres by exact integer edge functions (32 x 32 -> 64-bit products) with the
//   top-left fill rule of a y-down framebuffer;
// - window z interpolated linearly in window space (z/w for perspective views), attributes
//   perspective-correct.
#ifndef PENUMBRA_RASTER_CORE_GLSL
#define PENUMBRA_RASTER_CORE_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#include "bindings.glsl"

const float kNearW = 1e-5;
const float kGuard = 2.0;  // clip-space |x|, |y| <= kGuard w: window coordinates stay within 2^22 sub-texels
const float kSubpixel = 256.0;
// A triangle clipped by n planes has at most n + 3 vertices: 5 planes for the shadow tiles, 6 for the main view.
#ifndef RASTER_MAX_CLIPPED
#define RASTER_MAX_CLIPPED 9
#endif
const int kMaxClipped = RASTER_MAX_CLIPPED;
// Clip planes (bit masks for clipTriangle / needsClipping): w > kNearW, the guard band's four sides,
// and the main view's reversed-Z depth range 0 <= z <= w (near at z = w).
const uint kClipNearW = 1u, kClipGuard = 30u, kClipDepthNear = 32u, kClipDepthFar = 64u;

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

// Sets up the triangle (a, b, c) for a viewport (x, y, width, height) and scissor (x0, y0, x1, y1 exclusive) (all with w > kNearW, inside the guard band); false when
// nothing of it can cover a texel.
bool setupTriangle(vec4 viewport, uvec4 scissor, RasterVertex a, RasterVertex b, RasterVertex c, out RasterTriangleSetup t) {
    RasterVertex v[3] = RasterVertex[3](a, b, c);
    vec2 minWindow = vec2(1e30), maxWindow = vec2(-1e30);
    for (int i = 0; i < 3; ++i) {
        float invW = 1.0 / v[i].clip.w;
        vec3 ndc = v[i].clip.xyz * invW;
        vec2 window = viewport.xy + (ndc.xy * 0.5 + 0.5) * viewport.zw;
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
    lo = max(lo, ivec2(scissor.xy));
    hi = min(hi, ivec2(scissor.zw) - 1);
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

// Distance of a clip-space vertex to clip plane `plane` (bit index of kClip*, >= 0 inside).
float planeDistance(vec4 clip, int plane) {
    if (plane == 0) return clip.w - kNearW;
    if (plane == 5) return clip.w - clip.z;
    if (plane == 6) return clip.z;
    float g = kGuard * clip.w;
    if (plane == 1) return g - clip.x;
    if (plane == 2) return g + clip.x;
    if (plane == 3) return g - clip.y;
    return g + clip.y;
}

// Clips the triangle (Sutherland-Hodgman against the planes of the mask) into a fan; returns its vertex count.
int clipTriangle(RasterVertex v[3], uint planes, out RasterVertex polygon[kMaxClipped]) {
    polygon[0] = v[0]; polygon[1] = v[1]; polygon[2] = v[2];
    int count = 3;
    for (int plane = 0; plane < 7; ++plane) {
        if ((planes & (1u << plane)) == 0u) continue;
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

// Whether some vertex lies outside w > kNearW or the guard band (the rare case that clips).
bool needsClipping(RasterVertex v[3], uint planes) {
    for (int i = 0; i < 3; ++i)
        for (int plane = 0; plane < 7; ++plane)
            if ((planes & (1u << plane)) != 0u && planeDistance(v[i].clip, plane) < 0.0) return true;
    return false;
}

// Whether the piece can cover a pixel centre of the kRasterChunk^2 chunk at `origin`: no edge has
// all four corner centres outside.
bool overlapsChunk(RasterTriangleSetup t, ivec2 origin, int chunk) {
    ivec2 corners[4] = ivec2[4](texelCentre(origin.x, origin.y), texelCentre(origin.x + chunk - 1, origin.y),
                                texelCentre(origin.x, origin.y + chunk - 1),
                                texelCentre(origin.x + chunk - 1, origin.y + chunk - 1));
    for (int e = 0; e < 3; ++e) {
        ivec2 a = t.p[e], b = t.p[(e + 1) % 3];
        bool allOutside = true;
        for (int c = 0; c < 4; ++c) allOutside = allOutside && edgeSign(a, b, corners[c]) < 0;
        if (allOutside) return false;
    }
    return true;
}

// The base colour's alpha of the piece's material at a pixel centre: the texture at the
// perspective-correct uv, with the uv change from pixel `d` to its next pixel in x and y as gradients
// (the LOD rule of the fragment passes; d = the pixel itself, or its 2 x 2 quad's first pixel for the
// hardware's coarse derivatives). Every thread of a workgroup rasterizes the same instance (pass 1) or piece
// (pass 3), so the texture index is uniform; broadcasting it says so to the compiler.
float rasterBaseAlpha(RasterTriangleSetup t, vec3 weights, ivec2 d) {
    MaterialData material = materials[t.materialIndex];
    float alpha = material.baseColorFactor.a;
    if (material.baseColorTexture != 0u) {
        vec2 uv = perspectiveUv(t, weights);
        vec2 uvAtD = perspectiveUv(t, planeWeights(t, d.x, d.y));
        vec2 dx = perspectiveUv(t, planeWeights(t, d.x + 1, d.y)) - uvAtD;
        vec2 dy = perspectiveUv(t, planeWeights(t, d.x, d.y + 1)) - uvAtD;
        uint texture = subgroupBroadcastFirst(material.baseColorTexture - 1u);
        alpha *= textureLod(baseColorTextures[texture], uv, textureLevel(texture, dx, dy)).a;
    }
    return alpha;
}

uint boundsArea(ivec4 bounds) { return uint(bounds.z - bounds.x + 1) * uint(bounds.w - bounds.y + 1); }

#endif
