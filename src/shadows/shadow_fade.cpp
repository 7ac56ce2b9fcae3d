#include "shadows/shadow_fade.h"

#include <algorithm>

namespace penumbra {

float fadedShadowStrength(float distance, float scale, float fade) {
    return std::clamp((1.0f - distance * scale) * fade, 0.0f, 1.0f);
}

glm::vec2 squaredFadeScaleBias(float shadowDistance, float distanceFade) {
    const float maxSquared = shadowDistance * shadowDistance;
    const float start = shadowDistance * (1.0f - distanceFade);
    const float range = std::max(maxSquared - start * start, 1e-12f);
    return {1.0f / range, -start * start / range};
}

float distanceFadeStrength(ShadowFadeMode mode, float shadowDistance, float distanceFade, float viewDepth,
                           float cameraDistanceSquared) {
    if (mode == ShadowFadeMode::Squared) {
        const glm::vec2 scaleBias = squaredFadeScaleBias(shadowDistance, distanceFade);
        return 1.0f - std::clamp(cameraDistanceSquared * scaleBias.x + scaleBias.y, 0.0f, 1.0f);
    }
    return fadedShadowStrength(viewDepth, 1.0f / shadowDistance, 1.0f / distanceFade);
}

namespace {

// The cascade holding the point and its own fade (1 inside, 0 at its edge): see penumbra/shadows.glsl
// selectDirectionalCascade. cascadeIndex == count when none does.
std::pair<uint32_t, float> cascadeAndFade(const gpu_data::DirectionalShadowData& data, const glm::vec3& wsPosition,
                                          float viewDepth) {
    const uint32_t count = data.cascadeCount;
    const bool tight = data.cascadeFit == gpu_data::kCascadeFitTight;
    for (uint32_t i = 0; i < count; ++i) {
        const gpu_data::DirectionalCascade& cascade = data.cascades[i];
        if (tight) {
            // The last tight cascade ends at the farthest visible surface, short of the shadow distance in a
            // shallow view: it fades toward the shadow distance, as the sphere fit's last cascade does, not
            // toward its own end (which faded the back of every shallow view, a top-down one wholly).
            const float split = cascade.vsSplit, scale = i + 1 == count ? data.invShadowDistance : 1.0f / split;
            if (viewDepth < split) return {i, fadedShadowStrength(viewDepth, scale, data.invCascadeFade)};
            continue;
        }
        const glm::vec4 sphere = cascade.cullingSphere;
        const glm::vec3 d = wsPosition - glm::vec3(sphere);
        const float distanceSqr = glm::dot(d, d);
        if (distanceSqr < sphere.w) return {i, fadedShadowStrength(distanceSqr, cascade.invRadiusSquared, data.cascadeFadeScale)};
    }
    return {count, 0.0f};
}

}  // namespace

CascadeSelection selectCascade(const gpu_data::DirectionalShadowData& data, const glm::vec3& wsPosition,
                               float viewDepth, const glm::vec3& wsCamera) {
    CascadeSelection selection;
    const glm::vec3 fromCamera = wsPosition - wsCamera;
    if (data.fadeMode == gpu_data::kShadowFadeSquared) {
        const float d2 = glm::dot(fromCamera, fromCamera);
        selection.strength = 1.0f - std::clamp(d2 * data.squaredFadeScale + data.squaredFadeBias, 0.0f, 1.0f);
    } else {
        selection.strength = fadedShadowStrength(viewDepth, data.invShadowDistance, data.invDistanceFade);
    }
    const uint32_t count = data.cascadeCount;
    const auto [i, fade] = cascadeAndFade(data, wsPosition, viewDepth);
    if (i == count) selection.strength = 0.0f;  // beyond the last cascade: no shadow
    else if (i == count - 1) selection.strength *= fade;
    else selection.cascadeBlend = fade;
    // Blend only toward a next cascade whose sphere holds the point (spheres need not nest).
    if (selection.cascadeBlend < 1.0f && i + 1 < count && data.cascadeFit == gpu_data::kCascadeFitSphere) {
        const glm::vec4 next = data.cascades[i + 1].cullingSphere;
        const glm::vec3 d = wsPosition - glm::vec3(next);
        if (!(glm::dot(d, d) < next.w)) selection.cascadeBlend = 1.0f;
    }
    selection.cascadeIndex = i;
    return selection;
}

}  // namespace penumbra
