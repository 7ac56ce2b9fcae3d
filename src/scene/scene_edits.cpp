#include "scene/scene_edits.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace penumbra {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkIndex(const char* what, uint32_t index, size_t count) {
    if (index >= count)
        throw Error(std::string(what) + " " + std::to_string(index) + " does not exist (the scene has " +
                    std::to_string(count) + ")");
}

[[noreturn]] void invalid(const std::string& what, const std::string& why) { throw Error(what + ": " + why); }

void checkRange(const std::string& what, const char* field, float value, float lo, float hi) {
    if (!std::isfinite(value) || value < lo || value > hi)
        invalid(what, std::string(field) + " = " + std::to_string(value) + " is out of range (allowed " +
                          std::to_string(lo) + ".." + (hi > 1e30f ? std::string("inf") : std::to_string(hi)) + ")");
}

}  // namespace

void setInstanceWorldTransform(Scene& scene, uint32_t instance, const glm::mat4& worldFromObject) {
    checkIndex("instance", instance, scene.instances.size());
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(worldFromObject[c][r]))
                invalid("instance " + std::to_string(instance), "the transform has a non-finite element");
    Instance& target = scene.instances[instance];
    target.worldFromObject = worldFromObject;
    target.wsBounds = scene.meshes.at(target.meshIndex).osBounds.transformed(worldFromObject);
    scene.wsBounds.extend(target.wsBounds);
}

void replaceLight(Scene& scene, uint32_t light, const Light& value) {
    checkIndex("light", light, scene.lights.size());
    const std::string what = "light " + std::to_string(light);
    Light updated = value;
    if (!finite(updated.wsPosition) || !finite(updated.wsDirection) || !finite(updated.color))
        invalid(what, "position, direction and colour must be finite");
    const float length = glm::length(updated.wsDirection);
    if (!(length > 1e-6f)) invalid(what, "the direction has zero length");
    updated.wsDirection /= length;
    constexpr float kHuge = 3.0e38f;
    checkRange(what, "intensity", updated.intensity, 0.0f, kHuge);
    checkRange(what, "range", updated.range, 0.0f, kHuge);
    checkRange(what, "outerConeAngle", updated.outerConeAngle, 0.0f, 1.5707964f);
    checkRange(what, "innerConeAngle", updated.innerConeAngle, 0.0f, updated.outerConeAngle);
    checkRange(what, "shadowStrength", updated.shadowStrength, 0.0f, 1.0f);
    checkRange(what, "shadowBias", updated.shadowBias, 0.0f, kHuge);
    checkRange(what, "shadowNormalBias", updated.shadowNormalBias, 0.0f, kHuge);
    checkRange(what, "shadowNearPlane", updated.shadowNearPlane, 0.0f, kHuge);
    scene.lights[light] = updated;
}

void replaceMaterial(Scene& scene, uint32_t material, const Material& value) {
    checkIndex("material", material, scene.materials.size());
    const std::string what = "material " + std::to_string(material);
    if (value.baseColorTexture < -1 || value.baseColorTexture >= int(scene.textures.size()))
        invalid(what, "baseColorTexture " + std::to_string(value.baseColorTexture) + " does not exist");
    for (int i = 0; i < 4; ++i) checkRange(what, "baseColorFactor", value.baseColorFactor[i], 0.0f, 1.0f);
    checkRange(what, "metallic", value.metallic, 0.0f, 1.0f);
    checkRange(what, "roughness", value.roughness, 0.0f, 1.0f);
    checkRange(what, "alphaCutoff", value.alphaCutoff, 0.0f, 1.0f);
    scene.materials[material] = value;
}

}  // namespace penumbra
