#include "app/bench_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra {

std::vector<uint32_t> movingInstances(uint32_t instanceCount, double fraction) {
    // The small margin keeps 0.28 * 25 (7.000000000000001 in binary) at 7.
    const double wanted = std::ceil(std::clamp(fraction, 0.0, 1.0) * double(instanceCount) - 1e-9);
    const uint32_t moved = std::min(instanceCount, uint32_t(std::max(wanted, 0.0)));
    std::vector<uint32_t> indices(moved);
    for (uint32_t j = 0; j < moved; ++j) indices[j] = uint32_t(uint64_t(j) * instanceCount / moved);
    return indices;
}

glm::vec3 turnedAboutUp(const glm::vec3& direction, double degrees) {
    const double radians = glm::radians(std::fmod(degrees, 360.0));
    const float c = float(std::cos(radians)), s = float(std::sin(radians));
    // Right-handed rotation about +Y: x' = x cos + z sin, z' = -x sin + z cos.
    return {direction.x * c + direction.z * s, direction.y, -direction.x * s + direction.z * c};
}

float moveAmplitude(const Aabb& instanceBounds, const Aabb& sceneBounds) {
    const float sceneSize = sceneBounds.valid() ? glm::length(sceneBounds.extent()) : 0.0f;
    const float sceneShare = sceneSize > 0.0f ? 0.01f * sceneSize : 0.01f;
    if (!instanceBounds.valid()) return sceneShare;
    const glm::vec3 extent = instanceBounds.extent();
    const float own = 0.05f * std::max({extent.x, extent.y, extent.z});
    return own > 0.0f ? std::min(own, sceneShare) : sceneShare;
}

float moveOffset(float amplitude, uint64_t frame) {
    // sin's period is 20 pi frames: the argument is reduced first so that it stays exact on long runs.
    const double phase = std::fmod(0.1 * double(frame), 2.0 * std::numbers::pi);
    return amplitude * float(std::sin(phase));
}

BenchMotion::BenchMotion(const Scene& scene, double lightDegreesPerFrame, double moveFraction)
    : degrees_(lightDegreesPerFrame) {
    if (lightDegreesPerFrame > 0.0)
        for (uint32_t i = 0; i < scene.lights.size(); ++i)
            if (scene.lights[i].type == LightType::Directional)
                lights_.push_back({i, scene.lights[i].wsDirection, scene.lights[i]});
    for (uint32_t index : movingInstances(uint32_t(scene.instances.size()), moveFraction)) {
        const Instance& instance = scene.instances[index];
        instances_.push_back({index, instance.worldFromObject, moveAmplitude(instance.wsBounds, scene.wsBounds)});
    }
}

void BenchMotion::apply(Renderer& renderer, uint64_t frame) {
    const double degrees = std::fmod(degrees_ * double(frame), 360.0);
    for (TurnedLight& turned : lights_) {
        turned.light.wsDirection = turnedAboutUp(turned.direction, degrees);
        // --vary-settings changes which lights cast shadows (through setLight too): keep its choice.
        turned.light.shadows = renderer.scene().lights[turned.index].shadows;
        renderer.setLight(turned.index, turned.light);
    }
    for (const MovedInstance& moved : instances_) {
        const glm::vec3 offset(moveOffset(moved.amplitude, frame), 0.0f, 0.0f);
        renderer.setInstanceTransform(moved.index, glm::translate(glm::mat4(1.0f), offset) * moved.worldFromObject);
    }
}

}  // namespace penumbra
