#include "reference/area_light.h"

#include <cmath>
#include <limits>

namespace penumbra {

namespace {

// Two unit vectors that complete `axis` (unit) to an orthonormal frame.
void orthonormalFrame(const glm::vec3& axis, glm::vec3& t1, glm::vec3& t2) {
    t1 = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    t2 = glm::cross(axis, t1);
}

}  // namespace

glm::vec2 vogelDiskSample(uint32_t i, uint32_t n, float rotation) {
    const float r = std::sqrt((float(i) + 0.5f) / float(n));
    const float theta = float(i) * 2.39996323f + rotation;  // the golden angle
    return r * glm::vec2(std::cos(theta), std::sin(theta));
}

AreaLightRay areaLightRay(const Light& light, const glm::vec3& wsOrigin, glm::vec2 disk, float epsilon) {
    glm::vec3 t1, t2;
    AreaLightRay ray;
    if (light.type == LightType::Directional) {
        const glm::vec3 toSun = -glm::normalize(light.wsDirection);
        orthonormalFrame(toSun, t1, t2);
        const float tanRadius = std::tan(0.5f * glm::radians(light.shadowLightSize));
        ray.wsDirection = glm::normalize(toSun + tanRadius * (disk.x * t1 + disk.y * t2));
        ray.tFar = std::numeric_limits<float>::infinity();
        return ray;
    }
    const glm::vec3 toCentre = light.wsPosition - wsOrigin;
    const float distance = glm::length(toCentre);
    orthonormalFrame(distance > 0.0f ? toCentre / distance : -light.wsDirection, t1, t2);
    const glm::vec3 target = light.wsPosition + light.shadowLightSize * (disk.x * t1 + disk.y * t2);
    const glm::vec3 toTarget = target - wsOrigin;
    const float length = glm::length(toTarget);
    ray.wsDirection = length > 0.0f ? toTarget / length : -light.wsDirection;
    ray.tFar = std::max(length - epsilon, 0.0f);
    return ray;
}

}  // namespace penumbra
