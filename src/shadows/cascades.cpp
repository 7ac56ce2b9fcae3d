#include "shadows/cascades.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace penumbra {

float shadowDistance(const CameraView& camera, float maxDistance) {
    const float zFar = std::isfinite(camera.zFar) && camera.zFar > 0.0f ? camera.zFar : maxDistance;
    return std::max(std::min(maxDistance, zFar), camera.zNear);
}

std::vector<float> cascadeSplitDistances(const CameraView& camera, float distance, uint32_t cascadeCount,
                                         const std::array<float, 3>& ratios) {
    PENUMBRA_ASSERT(cascadeCount >= 1 && cascadeCount <= 4);
    std::vector<float> splits(cascadeCount);
    float previous = camera.zNear;
    for (uint32_t i = 0; i + 1 < cascadeCount; ++i) {
        // Settings validation refuses decreasing ratios; the clamp also keeps every split within
        // [zNear, distance] when the near plane lies beyond the first ratio's distance.
        splits[i] = std::clamp(ratios[i] * distance, previous, distance);
        previous = splits[i];
    }
    splits[cascadeCount - 1] = distance;
    return splits;
}

CascadeSphere frustumSliceSphere(const CameraView& camera, float vsNear, float vsFar) {
    const float tanHalfY = std::tan(0.5f * camera.yfov);
    const float tanHalfX = tanHalfY * camera.aspect;
    const float k2 = tanHalfX * tanHalfX + tanHalfY * tanHalfY;
    const float center = std::min(vsFar, 0.5f * (vsNear + vsFar) * (1.0f + k2));
    // Distance to the far ring; the near ring is at the same distance or closer by construction.
    const float dz = vsFar - center;
    CascadeSphere sphere;
    sphere.vsNear = vsNear;
    sphere.vsFar = vsFar;
    sphere.radius = std::sqrt(dz * dz + k2 * vsFar * vsFar);
    sphere.wsCenter = camera.wsPosition + glm::normalize(camera.wsForward) * center;
    return sphere;
}

std::vector<CascadeSphere> computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings) {
    const DirectionalShadowSettings& directional = settings.directional;
    const float distance = shadowDistance(camera, settings.maxDistance);
    const std::vector<float> splits =
        cascadeSplitDistances(camera, distance, directional.cascadeCount, directional.cascadeRatios);
    std::vector<CascadeSphere> spheres;
    spheres.reserve(splits.size());
    float vsNear = camera.zNear;
    for (float vsFar : splits) {
        spheres.push_back(frustumSliceSphere(camera, vsNear, vsFar));
        vsNear = vsFar;
    }
    return spheres;
}

glm::mat4 lightRotationFromWorld(const glm::vec3& wsDirection) {
    const glm::vec3 forward = glm::normalize(wsDirection);
    // Any fixed up vector works as long as it is the same every frame; avoid the degenerate one.
    const glm::vec3 up = std::abs(forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 lsUp = glm::cross(right, forward);
    glm::mat4 m(1.0f);  // rows = light axes: x = right, y = up, z = -forward
    m[0][0] = right.x;  m[1][0] = right.y;  m[2][0] = right.z;
    m[0][1] = lsUp.x;   m[1][1] = lsUp.y;   m[2][1] = lsUp.z;
    m[0][2] = -forward.x; m[1][2] = -forward.y; m[2][2] = -forward.z;
    return m;
}

CascadeLightView fitCascadeLightView(const glm::mat4& lightRotation, const CascadeSphere& sphere,
                                     uint32_t tileSize) {
    PENUMBRA_ASSERT(tileSize > 0);
    CascadeLightView view;
    view.halfExtent = sphere.radius;
    view.wsTexelSize = 2.0f * sphere.radius / float(tileSize);
    const glm::vec3 rsCenter = glm::vec3(lightRotation * glm::vec4(sphere.wsCenter, 1.0f));
    glm::vec3 snapped = rsCenter;
    if (view.wsTexelSize > 0.0f) {
        // Round (not floor): the sphere then sticks out of the box by at most half a texel, which the
        // filter-size shrink of the sampled sphere (seed 000 §4.6) more than covers.
        snapped.x = std::floor(rsCenter.x / view.wsTexelSize + 0.5f) * view.wsTexelSize;
        snapped.y = std::floor(rsCenter.y / view.wsTexelSize + 0.5f) * view.wsTexelSize;
    }
    glm::mat4 translation(1.0f);
    translation[3] = glm::vec4(-snapped, 1.0f);
    view.lightFromWorld = translation * lightRotation;
    view.lsSphereCenter = rsCenter - snapped;
    return view;
}

glm::mat4 orthoClipFromLight(float halfExtent, float nearDistance, float farDistance) {
    PENUMBRA_ASSERT(halfExtent > 0.0f && nearDistance + farDistance > 0.0f);
    const float depthRange = nearDistance + farDistance;
    glm::mat4 m(0.0f);
    m[0][0] = 1.0f / halfExtent;
    m[1][1] = -1.0f / halfExtent;  // Vulkan NDC y points down: light-space up -> top of the tile
    m[2][2] = -1.0f / depthRange;
    m[3][2] = nearDistance / depthRange;
    m[3][3] = 1.0f;
    return m;
}

}  // namespace penumbra
