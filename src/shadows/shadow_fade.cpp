#include "shadows/shadow_fade.h"

#include <algorithm>

namespace penumbra {

float fadedShadowStrength(float distance, float scale, float fade) {
    return std::clamp((1.0f - distance * scale) * fade, 0.0f, 1.0f);
}

CascadeSelection selectCascade(const gpu_data::DirectionalShadowData& data, const glm::vec3& wsPosition,
                               float viewDepth) {
    CascadeSelection selection;
    selection.strength = fadedShadowStrength(viewDepth, data.fade.x, data.fade.y);
    const uint32_t count = data.config.x;
    uint32_t i = 0;
    for (; i < count; ++i) {
        const glm::vec4 sphere = data.cullingSpheres[i];
        const glm::vec3 d = wsPosition - glm::vec3(sphere);
        const float distanceSqr = glm::dot(d, d);
        if (distanceSqr < sphere.w) {
            const float fade = fadedShadowStrength(distanceSqr, data.cascadeData[i].x, data.fade.z);
            if (i == count - 1) {
                selection.strength *= fade;
            } else {
                selection.cascadeBlend = fade;
            }
            break;
        }
    }
    if (i == count) selection.strength = 0.0f;  // seed 000 §3.5: beyond the last cascade
    // Blend only toward a next cascade whose sphere holds the point (spheres need not nest).
    if (selection.cascadeBlend < 1.0f && i + 1 < count) {
        const glm::vec4 next = data.cullingSpheres[i + 1];
        const glm::vec3 d = wsPosition - glm::vec3(next);
        if (!(glm::dot(d, d) < next.w)) selection.cascadeBlend = 1.0f;
    }
    selection.cascadeIndex = i;
    return selection;
}

}  // namespace penumbra
