#include "penumbra/scene_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "scene/mesh_utils.h"

namespace penumbra {

uint32_t SceneBuilder::addMaterial(const Material& material) {
    scene_.materials.push_back(material);
    return uint32_t(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::addTexture(Texture texture) {
    PENUMBRA_ASSERT(texture.rgba.channels == 4);
    scene_.textures.push_back(std::move(texture));
    return uint32_t(scene_.textures.size() - 1);
}

uint32_t SceneBuilder::addMesh(Mesh mesh) {
    mesh.osBounds = computeBounds(mesh.vertices);
    scene_.meshes.push_back(std::move(mesh));
    return uint32_t(scene_.meshes.size() - 1);
}

uint32_t SceneBuilder::addInstance(uint32_t meshIndex, const glm::mat4& worldFromObject, bool castShadows,
                                   std::string nodeName) {
    PENUMBRA_ASSERT(meshIndex < scene_.meshes.size());
    Instance instance;
    instance.meshIndex = meshIndex;
    instance.worldFromObject = worldFromObject;
    instance.castShadows = castShadows;
    instance.nodeName = std::move(nodeName);
    scene_.instances.push_back(std::move(instance));
    return uint32_t(scene_.instances.size() - 1);
}

uint32_t SceneBuilder::addLight(const Light& light) {
    scene_.lights.push_back(light);
    return uint32_t(scene_.lights.size() - 1);
}

void SceneBuilder::setCamera(const Camera& camera) { scene_.camera = camera; }

Scene SceneBuilder::build() {
    if (scene_.materials.empty()) {
        Material fallback;
        fallback.name = "default";
        scene_.materials.push_back(fallback);
    }
    for ([[maybe_unused]] const Mesh& mesh : scene_.meshes) PENUMBRA_ASSERT(mesh.materialIndex < scene_.materials.size());
    for ([[maybe_unused]] const Material& material : scene_.materials)
        PENUMBRA_ASSERT(material.baseColorTexture < int(scene_.textures.size()));
    computeWorldBounds(scene_);
    Scene result = std::move(scene_);
    scene_ = Scene{};
    return result;
}

Light makeDirectionalLight(glm::vec3 wsDirection, float intensityLux, glm::vec3 color) {
    Light light;
    light.type = LightType::Directional;
    light.wsDirection = glm::normalize(wsDirection);
    light.intensity = intensityLux;
    light.color = color;
    light.shadowNearPlane = 0.0f;
    return light;
}

Light makeSpotLight(glm::vec3 wsPosition, glm::vec3 wsDirection, float intensityCandela, float range,
                    float outerConeRadians, float innerConeRadians) {
    Light light;
    light.type = LightType::Spot;
    light.wsPosition = wsPosition;
    light.wsDirection = glm::normalize(wsDirection);
    light.intensity = intensityCandela;
    light.range = range;
    light.outerConeAngle = outerConeRadians;
    light.innerConeAngle = innerConeRadians;
    light.shadowNearPlane = 0.1f;
    light.shadowLightSize = defaultShadowLightSize(LightType::Spot);
    return light;
}

Light makePointLight(glm::vec3 wsPosition, float intensityCandela, float range) {
    Light light;
    light.type = LightType::Point;
    light.wsPosition = wsPosition;
    light.intensity = intensityCandela;
    light.range = range;
    light.shadowNearPlane = 0.1f;
    light.shadowLightSize = defaultShadowLightSize(LightType::Point);
    return light;
}

Camera makeLookAtCamera(glm::vec3 wsEye, glm::vec3 wsTarget, float yfovRadians, float zNear, float zFar) {
    const glm::vec3 forward = glm::normalize(wsTarget - wsEye);
    // Looking straight up or down: +Y cannot be the up vector, use -Z (the top of the image points away).
    const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(wsEye, wsTarget, up));
    camera.yfov = yfovRadians;
    camera.zNear = zNear;
    camera.zFar = zFar;
    return camera;
}

}  // namespace penumbra
