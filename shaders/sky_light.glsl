// The ambient term of the lit surfaces (render.ambient): the irradiance of the background gradient
// (tone_mapping.glsl) as a sky around the scene, whatever render.background shows. Written in the
// common subset of GLSL and C++ (glm), like tone_mapping.glsl: shade_surface.glsl includes it, and
// tests/unit/sky_light_test.cpp compiles the very same functions on the CPU.
//
// A Lambertian surface of albedo a under sky radiance L(w) leaves the radiance a E(n) / pi, with the
// irradiance E(n) = integral L(w) max(n.w, 0) dw. The gradient depends on the height w.y alone, so
// E / pi depends on n.y = y alone; the ambient radiance is ambient x baseColor x skyIrradiance(n).
//
// The classic hemisphere light (Akenine-Moller, Haines, Hoffman, "Real-Time Rendering", 4th ed.,
// 2018, chapter 10) takes a sky S above the horizon and a ground G below as constant:
//     E / pi = mix(G, S, 0.5 + 0.5 y)      ((1 + y) / 2: the cosine-weighted share of sky seen).
// With S and G the gradient's cosine-weighted means, 2 * integral_0^1 L(mu) mu dmu over mu = |w.y|,
// it is exact for y = 1 and y = -1, but our gradient is brightest at the horizon, which a tilted
// surface sees more of: it falls 22 % short for a vertical wall. So a horizon term (1 - y^2), zero
// at both poles, is added to make it exact at y = 0 too; with L = horizon + (zenith - horizon) wZ +
// (ground - horizon) wG the fit's weights are quadratics in y,
//     wZ(y) = 0.4 (1 + y) + (kWallZenith - 0.4) (1 - y^2)
//     wG(y) = 0.49375 (1 - y) + (kWallGround - 0.49375) (1 - y^2),
// within 3 % of the exact convolution for every normal (the unit test integrates the gradient):
//  - above, L = mix(horizon, zenith, sqrt(mu)): zenith weight 2 * integral mu^1.5 = 0.8 at y = 1
//    (0.4 = 0.8 / 2), and (2 / pi) * integral_0^1 sqrt(mu) sqrt(1 - mu^2) dmu = B(3/4, 3/2) / pi at y = 0;
//  - below, L = mix(horizon, ground, sqrt(min(4 mu, 1))): ground weight
//    2 * integral_0^1/4 2 mu^1.5 + 2 * integral_1/4^1 mu = 0.05 + 0.9375 = 0.9875 at y = -1, and
//    (2 / pi) * integral_0^1 sqrt(min(4 mu, 1)) sqrt(1 - mu^2) dmu (numerically) at y = 0.
#ifndef PENUMBRA_SKY_LIGHT_GLSL
#define PENUMBRA_SKY_LIGHT_GLSL
#include "tone_mapping.glsl"

#ifdef __cplusplus
namespace penumbra::gpu_data::look {
using namespace glm;
#endif

const float kWallZenith = 0.305104f;  // B(3/4, 3/2) / pi: the zenith's weight for a vertical surface
const float kWallGround = 0.447187f;  // the ground's weight for a vertical surface

// E(n) / pi of the gradient for the unit world-space normal n (glTF's +Y is up).
PENUMBRA_INLINE vec3 skyIrradiance(vec3 wsNormal) {
    float y = clamp(wsNormal.y, -1.0f, 1.0f);
    float horizon = 1.0f - y * y;
    float zenithWeight = 0.4f * (1.0f + y) + (kWallZenith - 0.4f) * horizon;
    float groundWeight = 0.49375f * (1.0f - y) + (kWallGround - 0.49375f) * horizon;
    return kSkyHorizon + (kSkyZenith - kSkyHorizon) * zenithWeight + (kSkyGround - kSkyHorizon) * groundWeight;
}

// The ambient radiance leaving a surface of `baseColor` facing `wsNormal`; `ambient` = render.ambient
// (0: none at all, 1: the sky as bright as the background shows it).
PENUMBRA_INLINE vec3 ambientRadiance(vec3 wsNormal, vec3 baseColor, float ambient) {
    return ambient * skyIrradiance(wsNormal) * baseColor;
}

#ifdef __cplusplus
}  // namespace penumbra::gpu_data::look
#endif
#endif
