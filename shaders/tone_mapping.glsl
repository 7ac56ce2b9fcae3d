// The display transform of the colour output and the background behind the scene
// (render.toneMapping and render.background). Written in the common subset of GLSL and C++ (glm),
// like shaders/shared/: the lit pass and shaders/background.frag.glsl include it, and
// tests/unit/tone_mapping_test.cpp compiles the very same functions on the CPU.
#ifndef PENUMBRA_TONE_MAPPING_GLSL
#define PENUMBRA_TONE_MAPPING_GLSL
#include "scene_structs.h"

#ifdef __cplusplus
namespace penumbra::gpu_data::look {
using namespace glm;
#endif

// Khronos PBR Neutral, from the formulas of its specification (Khronos Group, "PBR Neutral Tone
// Mapping", 2024, github.com/KhronosGroup/ToneMapping, PBR_Neutral/README.md). Below a peak channel
// of kNeutralStart a colour only loses a small offset (about the 4 % Fresnel reflectance of a
// dielectric, so a base colour lit by 1 shows close to its own sRGB value; the offset fades out
// quadratically below 0.08), above it the peak is compressed toward 1 (reached at infinity) and the
// colour desaturated toward white by kNeutralDesaturation.
const float kNeutralStart = 0.76f;  // 0.8 - 0.04
const float kNeutralDesaturation = 0.15f;

PENUMBRA_INLINE vec3 toneMapNeutral(vec3 color) {
    float low = min(color.r, min(color.g, color.b));
    float offset = low < 0.08f ? low - 6.25f * low * low : 0.04f;
    color -= vec3(offset);
    float peak = max(color.r, max(color.g, color.b));
    if (peak < kNeutralStart) return color;
    float d = 1.0f - kNeutralStart;
    float newPeak = 1.0f - d * d / (peak + d - kNeutralStart);
    color *= newPeak / peak;
    float desaturate = 1.0f - 1.0f / (kNeutralDesaturation * (peak - newPeak) + 1.0f);
    return mix(color, vec3(newPeak), desaturate);
}

// A fitted ACES filmic curve: Krzysztof Narkowicz's rational fit of the ACES reference rendering and
// output transforms ("ACES Filmic Tone Mapping Curve", 2016, knarkowicz.wordpress.com),
// f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) per channel, clamped to [0, 1]. It rises
// monotonically and reaches 1 at x = (0.56 + sqrt(0.3584)) / 0.16, about 7.24 (its white point).
PENUMBRA_INLINE vec3 toneMapAces(vec3 x) {
    vec3 curve = (x * (2.51f * x + vec3(0.03f))) / (x * (2.43f * x + vec3(0.59f)) + vec3(0.14f));
    return clamp(curve, vec3(0.0f), vec3(1.0f));
}

// Linear display values (sRGB encoding follows in the colour target) of exposed linear radiance;
// `mode` is a kToneMap* constant (FrameData.toneMapping). kToneMapNone leaves the values as they are
// (the target clamps them): linear values, no display transform.
PENUMBRA_INLINE vec3 toneMap(vec3 radiance, uint mode) {
    if (mode == kToneMapNeutral) return toneMapNeutral(max(radiance, vec3(0.0f)));
    if (mode == kToneMapAces) return toneMapAces(max(radiance, vec3(0.0f)));
    return radiance;
}

// The sky gradient (render.background: gradient) as linear radiance seen along a world-space
// direction (glTF's +Y is up): horizon haze to a blue zenith above, to a dark ground 15 degrees
// below. Continuous at the horizon; what the camera sees does not depend on the output size.
const vec3 kSkyZenith = vec3(0.16f, 0.27f, 0.52f);
const vec3 kSkyHorizon = vec3(0.64f, 0.70f, 0.78f);
const vec3 kSkyGround = vec3(0.21f, 0.20f, 0.19f);

PENUMBRA_INLINE vec3 backgroundRadiance(vec3 wsDirection) {
    float up = clamp(wsDirection.y / max(length(wsDirection), 1e-20f), -1.0f, 1.0f);
    if (up >= 0.0f) return mix(kSkyHorizon, kSkyZenith, sqrt(up));
    return mix(kSkyHorizon, kSkyGround, sqrt(min(-4.0f * up, 1.0f)));
}

#ifdef __cplusplus
}  // namespace penumbra::gpu_data::look
#endif
#endif
