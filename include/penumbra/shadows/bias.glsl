// How a shadow lookup keeps a surface from shadowing itself, for directional, spot and point lights
// alike. Three modes (kShadowBias*, the setting shadows.bias):
// - normal (Catlike Coding "Directional Shadows", Normal Bias): the lookup moves along the shading
//   normal by shadowNormalBias units of one texel diagonal x (1 + filter / 2): the classic rule;
// - scaledNormal: the same offset along the triangle's normal, times sin(N, L): a plane at angle θ to
//   the light needs a depth margin of tan θ per texel of filter reach, and an offset b along N gives b /
//   cos θ, so b ∝ sin θ is just enough, and no offset (no peter-panning) where the light hits head-on;
// - receiverPlane (receiver plane depth bias, Isidoro, "Shadow Mapping: GPU-based Tips and Techniques",
//   GDC 2006): no offset; every texel a filter reads is compared with the depth the receiver's plane
//   has at that texel's centre (tent.glsl penumbraCompareBilinear; the plane's depth
//   gradient in the tile comes from the triangle's normal), less a margin of kPlaneSlopeMargin of the
//   plane's depth change over one texel x shadowNormalBias, plus a rounding epsilon.
// In every mode the light's shadowBias adds shadowBias x the receiver's depth slope per texel (the
// rasterizer's slope-scale bias, applied here so the caster pass writes exact depth; Catlike Coding
// "Directional Shadows", Configurable Biases).
#ifndef PENUMBRA_SHADOW_BIAS_GLSL
#define PENUMBRA_SHADOW_BIAS_GLSL
#include "shadow_structs.h"

struct ShadowReceiver {
    vec3 wsPosition;
    vec3 wsNormal;           // shading normal, turned toward the camera
    vec3 wsGeometricNormal;  // the triangle's normal (screen derivatives), on the side of wsNormal
};

struct ShadowBiasParams {
    uint mode;            // kShadowBias*
    float normalBias;     // the light's shadowNormalBias: a multiplier of the automatic bias
    float slopeBias;      // the light's shadowBias
    float wsTexel;        // world size of one shadow texel at the receiver
    float footprint;      // normal-offset unit in texels: (1 + filter / 2) x sqrt(2)
    float clipDepthBias;  // constant clip-space depth bias (spot.depthBias), else 0
};

struct ShadowLookup {
    vec3 uvDepth;        // atlas u, v and the depth to compare, biases applied
    vec2 depthGradient;  // the receiver plane's depth per texel along u, v
    bool perTexelPlane;  // receiverPlane mode: compare each texel with the plane (else one depth for all 4 gathered texels)
    float w;             // the projection's w (perspective tiles); <= 0: behind the light
};

const float kMinBiasNDotL = 0.1;               // planes tilted toward 84° count as 84°: a finite bias
const float kReceiverPlaneDepthEpsilon = 1e-5; // depth units: rasterizer vs shader rounding
const float kPlaneSlopeMargin = 0.5;           // of the plane's depth change over one texel (u + v)

// The plane normal used for biases, tilted toward the light until N·L >= kMinBiasNDotL.
vec3 biasPlaneNormal(vec3 wsNormal, vec3 wsToLight) {
    float nDotL = dot(wsNormal, wsToLight);
    if (nDotL >= kMinBiasNDotL) return wsNormal;
    vec3 tangent = wsNormal - nDotL * wsToLight;
    float length2 = dot(tangent, tangent);
    if (length2 < 1e-12) return wsToLight;
    return tangent * inversesqrt(length2) * sqrt(1.0 - kMinBiasNDotL * kMinBiasNDotL) + wsToLight * kMinBiasNDotL;
}

// The depth gradient (depth per atlas texel along u and v) of the plane through wsPosition with normal
// wsNormal, as atlasFromWorld (orthographic or perspective) maps it: two tangents through the
// projection's Jacobian at the point, then the slope of depth over (u, v).
vec2 receiverPlaneDepthGradient(mat4 atlasFromWorld, vec3 wsPosition, vec3 wsNormal, float atlasSize) {
    vec3 t1 = normalize(cross(wsNormal, abs(wsNormal.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 t2 = cross(wsNormal, t1);
    vec4 h = atlasFromWorld * vec4(wsPosition, 1.0);
    vec3 uvDepth = h.xyz / h.w;
    vec4 d1 = atlasFromWorld * vec4(t1, 0.0), d2 = atlasFromWorld * vec4(t2, 0.0);
    vec3 a = (d1.xyz - uvDepth * d1.w) / h.w, b = (d2.xyz - uvDepth * d2.w) / h.w;
    a.xy *= atlasSize;
    b.xy *= atlasSize;
    float det = a.x * b.y - a.y * b.x;
    if (abs(det) < 1e-20) return vec2(0.0);
    return vec2(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
}

// Where the lookup projects from: the receiver, moved along a normal in the normal-offset modes.
vec3 biasedLookupPosition(ShadowReceiver r, vec3 wsToLight, ShadowBiasParams b) {
    float unit = b.normalBias * b.footprint * b.wsTexel;
    if (b.mode == kShadowBiasNormal) return r.wsPosition + r.wsNormal * unit;
    if (b.mode == kShadowBiasScaledNormal) {
        float nDotL = clamp(dot(r.wsGeometricNormal, wsToLight), 0.0, 1.0);
        return r.wsPosition + r.wsGeometricNormal * (unit * sqrt(1.0 - nDotL * nDotL));
    }
    return r.wsPosition;
}

// The biased lookup of one tile: project wsLookup (biasedLookupPosition), then subtract the
// slope-scale bias and, for receiverPlane, the plane's half-texel margin.
ShadowLookup shadowLookup(mat4 atlasFromWorld, ShadowReceiver r, vec3 wsLookup, vec3 wsToLight, ShadowBiasParams b,
                          float atlasSize) {
    ShadowLookup lookup;
    vec4 h = atlasFromWorld * vec4(wsLookup, 1.0);
    h.z -= b.clipDepthBias;  // clip space, before the divide
    lookup.w = h.w;
    lookup.uvDepth = h.w > 0.0 ? h.xyz / h.w : vec3(0.0, 0.0, 2.0);
    vec3 planeNormal = biasPlaneNormal(r.wsGeometricNormal, wsToLight);
    vec2 gradient = receiverPlaneDepthGradient(atlasFromWorld, r.wsPosition, planeNormal, atlasSize);
    vec2 slope = abs(gradient);
    lookup.uvDepth.z -= b.slopeBias * max(slope.x, slope.y);
    lookup.depthGradient = gradient;
    lookup.perTexelPlane = b.mode == kShadowBiasReceiverPlane;
    if (lookup.perTexelPlane)
        lookup.uvDepth.z -= b.normalBias * kPlaneSlopeMargin * (slope.x + slope.y) + kReceiverPlaneDepthEpsilon;
    return lookup;
}
#endif
