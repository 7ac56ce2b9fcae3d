#include "shadows/light_reservation.h"

#include <array>
#include <cmath>

#include "core/error.h"

#include "shadows/caster_culling.h"

namespace penumbra {

namespace {

bool anyCasterInShadowVolume(const Scene& scene, const std::vector<CascadeSphere>& spheres,
                             const std::vector<uint32_t>& casters, const glm::mat4& lightRotation) {
    std::array<glm::vec3, 4> rsCenters;  // at most 4 cascades
    PENUMBRA_ASSERT(spheres.size() <= rsCenters.size());
    for (size_t i = 0; i < spheres.size(); ++i) rsCenters[i] = glm::vec3(lightRotation * glm::vec4(spheres[i].wsCenter, 1.0f));
    const glm::mat3 rotation(lightRotation);
    const glm::mat3 absRotation(glm::abs(rotation[0]), glm::abs(rotation[1]), glm::abs(rotation[2]));
    for (uint32_t casterIndex : casters) {
        const Aabb& ws = scene.instances[casterIndex].wsBounds;
        const glm::vec3 center = rotation * ws.center();
        const glm::vec3 halfExtent = absRotation * (0.5f * ws.extent());
        const Aabb rs{center - halfExtent, center + halfExtent};
        for (size_t i = 0; i < spheres.size(); ++i) {
            if (intersectsExtrudedSphere(rs, rsCenters[i], spheres[i].radius)) return true;
        }
    }
    return false;
}

}  // namespace

void reserveDirectionalShadows(const Scene& scene, const std::vector<CascadeSphere>& spheres,
                               const std::vector<uint32_t>& casters, uint32_t cascadeCount,
                               std::vector<ReservedDirectionalLight>& reserved) {
    reserved.clear();
    for (uint32_t i = 0; i < scene.lights.size() && reserved.size() < gpu_data::kMaxShadowedDirectionalLights; ++i) {
        const Light& light = scene.lights[i];
        if (light.type != LightType::Directional) continue;
        if (light.shadows == LightShadows::None || !(light.shadowStrength > 0.0f)) continue;
        if (glm::dot(light.wsDirection, light.wsDirection) <= 0.0f) continue;
        const glm::mat4 rotation = lightRotationFromWorld(light.wsDirection);
        if (!anyCasterInShadowVolume(scene, spheres, casters, rotation)) continue;
        ReservedDirectionalLight entry;
        entry.sceneLightIndex = i;
        entry.strength = light.shadowStrength;
        entry.firstTile = uint32_t(reserved.size()) * cascadeCount;  // consecutive tiles per light
        entry.normalBias = light.shadowNormalBias;
        entry.slopeScaleBias = light.shadowBias;
        entry.soft = light.shadows != LightShadows::Hard;
        if (light.shadows == LightShadows::Pcss)
            entry.pcssTanRadius = std::tan(0.5f * glm::radians(light.shadowLightSize));
        entry.nearPlaneOffset = light.shadowNearPlane;
        entry.wsDirection = glm::normalize(light.wsDirection);
        reserved.push_back(entry);
    }
}

std::vector<ReservedDirectionalLight> reserveDirectionalShadows(const Scene& scene,
                                                                const std::vector<CascadeSphere>& spheres,
                                                                const std::vector<uint32_t>& casters,
                                                                uint32_t cascadeCount) {
    std::vector<ReservedDirectionalLight> reserved;
    reserveDirectionalShadows(scene, spheres, casters, cascadeCount, reserved);
    return reserved;
}

}  // namespace penumbra
