// Settings defaults that depend on the scene (penumbra/settings.h: applySceneDefaults).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "penumbra/camera.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

namespace penumbra {

namespace {

// A scene that lies wholly within this distance of the camera is far smaller than the default
// maxDistance suits (a scene in kilometres, or a tiny object seen from close by).
constexpr float kSmallestReach = 1.0f;

float farthestCornerDistance(const Aabb& bounds, const glm::vec3& from) {
    float farthest = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, glm::length(corner - from));
    }
    return farthest;
}

float nearestPointDistance(const Aabb& bounds, const glm::vec3& from) {
    return glm::length(glm::clamp(from, bounds.min, bounds.max) - from);
}

std::string formatDistance(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", double(value));
    return text;
}

}  // namespace

std::vector<std::string> applySceneDefaults(Settings& settings, const Scene& scene, const CameraView& view) {
    std::vector<std::string> warnings;
    if (settings.userSet("shadows.maxDistance") || !scene.wsBounds.valid()) return warnings;
    const float defaultDistance = ShadowSettings{}.maxDistance;
    const float nearest = nearestPointDistance(scene.wsBounds, view.wsPosition);
    float reach = farthestCornerDistance(scene.wsBounds, view.wsPosition);
    if (std::isfinite(view.zFar)) reach = std::min(reach, view.zFar);
    const bool allBeyond = nearest > defaultDistance;  // no surface would get a directional shadow
    const bool allClose = reach < kSmallestReach;      // the cascades would spend 99 % of their texels on nothing
    if (!std::isfinite(reach) || !(allBeyond || allClose)) return warnings;
    const float chosen = std::max(reach, 0.001f);  // the smallest maxDistance settings allow
    settings.shadows.maxDistance = chosen;
    warnings.push_back("shadows.maxDistance is not set and the scene lies " + formatDistance(nearest) + " to " +
                       formatDistance(reach) + " units from the camera, " +
                       (allBeyond ? "beyond" : "far within") + " the default " + formatDistance(defaultDistance) +
                       "; using " + formatDistance(chosen) + " (set shadows.maxDistance to choose)");
    return warnings;
}

}  // namespace penumbra
