#pragma once
// Changes to a loaded scene between frames (Renderer::setInstanceTransform, setLight, setMaterial),
// validated like the glTF loader validates its input: a bad value throws penumbra::Error naming it
// and leaves the scene as it was.
#include <cstdint>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// Sets the instance's world transform and bounds (Scene::wsBounds grows to hold them).
void setInstanceWorldTransform(Scene& scene, uint32_t instance, const glm::mat4& worldFromObject);
// Replaces a light; its direction is normalized.
void replaceLight(Scene& scene, uint32_t light, const Light& value);
void replaceMaterial(Scene& scene, uint32_t material, const Material& value);

}  // namespace penumbra
