#include "scene/scene_edits.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "scene/scene_validation.h"

namespace penumbra {

namespace {

void checkIndex(const char* what, uint32_t index, size_t count) {
    if (index >= count)
        throw Error(std::string(what) + " " + std::to_string(index) + " does not exist (the scene has " +
                    std::to_string(count) + ")");
}

}  // namespace

void setInstanceWorldTransform(Scene& scene, uint32_t instance, const glm::mat4& worldFromObject) {
    checkIndex("instance", instance, scene.instances.size());
    Instance updated = scene.instances[instance];
    updated.worldFromObject = worldFromObject;
    validateInstance(scene, updated, "instance " + std::to_string(instance));
    Instance& target = scene.instances[instance];
    target.worldFromObject = worldFromObject;
    target.wsBounds = scene.meshes.at(target.meshIndex).osBounds.transformed(worldFromObject);
    scene.wsBounds.extend(target.wsBounds);
}

void replaceLight(Scene& scene, uint32_t light, const Light& value) {
    checkIndex("light", light, scene.lights.size());
    Light updated = value;
    const float length = glm::length(updated.wsDirection);
    if (std::isfinite(length) && length > 1e-6f) updated.wsDirection /= length;
    validateLight(updated, "light " + std::to_string(light));
    scene.lights[light] = updated;
}

void replaceMaterial(Scene& scene, uint32_t material, const Material& value) {
    checkIndex("material", material, scene.materials.size());
    validateMaterial(value, scene.textures.size(), "material " + std::to_string(material));
    scene.materials[material] = value;
}

}  // namespace penumbra
