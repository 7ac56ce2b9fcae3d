#include "scene/scene_validation.h"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "core/error.h"

namespace penumbra {

namespace {

constexpr float kHuge = 3.0e38f;
constexpr float kHalfPi = 1.5707964f;
constexpr float kPi = 3.14159265f;

std::string formatNumber(float value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

[[noreturn]] void invalid(const std::string& what, const std::string& why) { throw Error(what + ": " + why); }

void checkRange(const std::string& what, const char* field, float value, float lo, float hi) {
    if (!std::isfinite(value) || value < lo || value > hi)
        invalid(what, std::string(field) + " = " + formatNumber(value) + " is out of range (allowed " + formatNumber(lo) +
                          ".." + (hi >= kHuge ? std::string("inf") : formatNumber(hi)) + ")");
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

std::string named(const char* kind, size_t index, const std::string& name) {
    return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

void validateMesh(const Mesh& mesh, size_t materialCount, const std::string& what) {
    if (mesh.materialIndex >= materialCount)
        invalid(what, "material " + std::to_string(mesh.materialIndex) + " does not exist (the scene has " +
                          std::to_string(materialCount) + ")");
    if (mesh.vertices.size() > size_t(INT32_MAX)) invalid(what, "more than 2^31 vertices");
    if (mesh.indices.size() % 3 != 0) invalid(what, "the index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vertex& v = mesh.vertices[i];
        if (!finite(v.osPosition) || !finite(v.osNormal) || !std::isfinite(v.uv.x) || !std::isfinite(v.uv.y))
            invalid(what, "vertex " + std::to_string(i) + " is not finite");
        if (glm::any(glm::greaterThan(glm::abs(v.osPosition), glm::vec3(kMaxWorldCoordinate))))
            invalid(what, "vertex " + std::to_string(i) + " lies beyond " + formatNumber(kMaxWorldCoordinate));
    }
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= mesh.vertices.size())
            invalid(what, "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                              ", not below the vertex count " + std::to_string(mesh.vertices.size()));
}

void validateTexture(const Texture& texture, const std::string& what) {
    const Image& image = texture.rgba;
    if (image.channels != 4 || image.width == 0 || image.height == 0 ||
        image.pixels.size() != size_t(image.width) * image.height * 4)
        invalid(what, "must be RGBA8 with width x height x 4 bytes");
}

}  // namespace

void validateInstance(const Scene& scene, const Instance& instance, const std::string& what) {
    if (instance.meshIndex >= scene.meshes.size())
        invalid(what, "mesh " + std::to_string(instance.meshIndex) + " does not exist (the scene has " +
                          std::to_string(scene.meshes.size()) + ")");
    if (!finite(instance.worldFromObject)) invalid(what, "the transform has a non-finite element");
    const Aabb bounds = scene.meshes[instance.meshIndex].osBounds.transformed(instance.worldFromObject);
    if (bounds.valid() && (!finite(bounds.min) || !finite(bounds.max) ||
                           glm::any(glm::greaterThan(glm::max(glm::abs(bounds.min), glm::abs(bounds.max)),
                                                     glm::vec3(kMaxWorldCoordinate)))))
        invalid(what, "its world bounds reach beyond " + formatNumber(kMaxWorldCoordinate));
}

void validateLight(const Light& light, const std::string& what) {
    if (int(light.type) < 0 || int(light.type) > int(LightType::Point)) invalid(what, "unknown type");
    if (int(light.shadows) < 0 || int(light.shadows) > int(LightShadows::Pcss)) invalid(what, "unknown shadow mode");
    if (!finite(light.wsPosition) || !finite(light.wsDirection) || !finite(light.color))
        invalid(what, "position, direction and colour must be finite");
    if (glm::any(glm::greaterThan(glm::abs(light.wsPosition), glm::vec3(kMaxWorldCoordinate))))
        invalid(what, "its position lies beyond " + formatNumber(kMaxWorldCoordinate));
    if (std::abs(glm::length(light.wsDirection) - 1.0f) > 1e-3f) invalid(what, "the direction must be a unit vector");
    for (int c = 0; c < 3; ++c) checkRange(what, "color", light.color[c], 0.0f, kHuge);
    checkRange(what, "intensity", light.intensity, 0.0f, kHuge);
    checkRange(what, "range", light.range, 0.0f, kHuge);
    checkRange(what, "outerConeAngle", light.outerConeAngle, 0.0f, kHalfPi);
    checkRange(what, "innerConeAngle", light.innerConeAngle, 0.0f, light.outerConeAngle);
    checkRange(what, "shadowStrength", light.shadowStrength, 0.0f, 1.0f);
    checkRange(what, "shadowBias", light.shadowBias, 0.0f, kHuge);
    checkRange(what, "shadowNormalBias", light.shadowNormalBias, 0.0f, kHuge);
    checkRange(what, "shadowNearPlane", light.shadowNearPlane, 0.0f, kHuge);
    checkRange(what, "shadowLightSize", light.shadowLightSize, 0.0f, light.type == LightType::Directional ? 20.0f : kHuge);
}

void validateMaterial(const Material& material, size_t textureCount, const std::string& what) {
    if (material.baseColorTexture < -1 || material.baseColorTexture >= int64_t(textureCount))
        invalid(what, "baseColorTexture " + std::to_string(material.baseColorTexture) + " does not exist (the scene has " +
                          std::to_string(textureCount) + " textures)");
    for (int i = 0; i < 4; ++i) checkRange(what, "baseColorFactor", material.baseColorFactor[i], 0.0f, 1.0f);
    checkRange(what, "metallic", material.metallic, 0.0f, 1.0f);
    checkRange(what, "roughness", material.roughness, 0.0f, 1.0f);
    checkRange(what, "alphaCutoff", material.alphaCutoff, 0.0f, kHuge);
    if (int(material.alphaMode) < 0 || int(material.alphaMode) > int(AlphaMode::Blend)) invalid(what, "unknown alphaMode");
    if (int(material.shadows) < 0 || int(material.shadows) > int(MaterialShadowMode::Off))
        invalid(what, "unknown shadow mode");
}

void validateCamera(const Camera& camera, const std::string& what) {
    if (!finite(camera.worldFromView)) invalid(what, "the transform has a non-finite element");
    for (int axis = 0; axis < 3; ++axis)
        if (!(glm::length(glm::vec3(camera.worldFromView[axis])) > 1e-12f))
            invalid(what, "the transform is degenerate (an axis has zero length)");
    if (!(camera.yfov > 0.0f && camera.yfov < kPi)) invalid(what, "yfov = " + formatNumber(camera.yfov) + " must be in (0, pi)");
    if (!(std::isfinite(camera.zNear) && camera.zNear > 0.0f))
        invalid(what, "zNear = " + formatNumber(camera.zNear) + " must be finite and > 0");
    if (!(camera.zFar > camera.zNear))
        invalid(what, "zFar = " + formatNumber(camera.zFar) + " must be greater than zNear = " + formatNumber(camera.zNear));
}

namespace {

void validateSceneObjects(const Scene& scene) {
    if (scene.materials.empty() && !scene.meshes.empty()) invalid("materials", "a scene with meshes needs a material");
    for (size_t i = 0; i < scene.textures.size(); ++i) validateTexture(scene.textures[i], named("texture", i, scene.textures[i].name));
    for (size_t i = 0; i < scene.materials.size(); ++i)
        validateMaterial(scene.materials[i], scene.textures.size(), named("material", i, scene.materials[i].name));
    for (size_t i = 0; i < scene.meshes.size(); ++i)
        validateMesh(scene.meshes[i], scene.materials.size(), named("mesh", i, scene.meshes[i].name));
    for (size_t i = 0; i < scene.instances.size(); ++i)
        validateInstance(scene, scene.instances[i], named("instance", i, scene.instances[i].nodeName));
    for (size_t i = 0; i < scene.lights.size(); ++i) validateLight(scene.lights[i], named("light", i, scene.lights[i].name));
    if (scene.camera) validateCamera(*scene.camera, named("camera", 0, scene.camera->name));
}

}  // namespace

void validateScene(const Scene& scene) {
    try {
        validateSceneObjects(scene);
    } catch (const Error& e) {
        throw Error(std::string("scene: ") + e.what());
    }
}

}  // namespace penumbra
