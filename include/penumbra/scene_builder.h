#pragma once
// Programmatic scenes (the demo scene, tests, canonical test scenes) and simple shapes.
// Shapes are triangle lists with counter-clockwise front faces (glTF) and outward normals.
#include <cmath>
#include <cstdint>
#include <string>

#include <penumbra/scene.h>

namespace penumbra {

class SceneBuilder {
public:
    uint32_t addMaterial(const Material& material);
    uint32_t addTexture(Texture texture);
    uint32_t addMesh(Mesh mesh);  // computes osBounds
    uint32_t addInstance(uint32_t meshIndex, const glm::mat4& worldFromObject, bool castShadows = true,
                         std::string nodeName = "");
    uint32_t addLight(const Light& light);
    void setCamera(const Camera& camera);
    // Computes instance wsBounds and Scene::wsBounds; adds a default material if there is none.
    Scene build();

private:
    Scene scene_;
};

// The checks every scene passes before the renderer or the reference uses it (Renderer's constructor
// runs them; build() does not): every index in range, every number finite and within its range.
// Throws penumbra::Error naming the first bad object and value, e.g. "scene: mesh 3 'wheel': index 17
// is 40, not below the vertex count 12".
void validateScene(const Scene& scene);

Mesh makeBoxMesh(glm::vec3 halfExtents, uint32_t materialIndex);  // centred, flat normals, per-face UVs
Mesh makeSphereMesh(float radius, uint32_t materialIndex, int segments = 48, int rings = 24);
Mesh makePlaneMesh(glm::vec2 size, uint32_t materialIndex, float uvScale = 1.0f);  // XZ plane at y=0 facing +Y
Mesh makeQuadMesh(glm::vec2 size, uint32_t materialIndex);  // XY quad at z=0 facing +Z, uv (0,0) top-left
Mesh makeCylinderMesh(float radius, float height, uint32_t materialIndex, int segments = 32);  // y in [0, height]

// Lights: directions are where the light travels; they are normalized here. Shadow settings take
// the glTF extras' defaults (soft, strength 1, near plane 0 directional / 0.1 spot and point).
Light makeDirectionalLight(glm::vec3 wsDirection, float intensityLux, glm::vec3 color = glm::vec3(1));
Light makeSpotLight(glm::vec3 wsPosition, glm::vec3 wsDirection, float intensityCandela, float range,
                    float outerConeRadians, float innerConeRadians);
Light makePointLight(glm::vec3 wsPosition, float intensityCandela, float range);
Camera makeLookAtCamera(glm::vec3 wsEye, glm::vec3 wsTarget, float yfovRadians, float zNear = 0.1f,
                        float zFar = INFINITY);

}  // namespace penumbra
