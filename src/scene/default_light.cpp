#include "scene/default_light.h"

#include <glm/gtc/constants.hpp>

namespace penumbra {

bool addDefaultSunIfUnlit(Scene& scene) {
    if (!scene.lights.empty()) return false;
    Light sun;
    sun.name = "default sun";
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    sun.color = glm::vec3(1.0f, 0.97f, 0.92f);
    sun.wsDirection = glm::normalize(glm::vec3(0.45f, -1.0f, -0.35f));
    sun.shadows = LightShadows::Soft;
    scene.lights.push_back(sun);
    return true;
}

}  // namespace penumbra
