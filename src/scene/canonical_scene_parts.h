#pragma once
// Building blocks of the canonical scenes (canonical_scenes.cpp, canonical_scenes_more.cpp); internal.
#include <cmath>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene.h"
#include "penumbra/scene_builder.h"

namespace penumbra::canonical {

inline glm::mat4 at(glm::vec3 wsPosition) { return glm::translate(glm::mat4(1.0f), wsPosition); }

inline glm::mat4 rotated(glm::mat4 pose, float degrees, glm::vec3 axis) {
    return glm::rotate(pose, glm::radians(degrees), axis);
}

inline Material colored(const char* name, glm::vec3 rgb) {
    Material material;
    material.name = name;
    material.baseColorFactor = glm::vec4(rgb, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.8f;
    return material;
}

// A sun `elevation` degrees above the horizon; azimuth 0 puts it straight behind a camera that looks
// along -Z (shadows point away from the camera), positive azimuths move it toward +X.
inline Light sunFrom(float elevationDegrees, float azimuthDegrees) {
    const float e = glm::radians(elevationDegrees), a = glm::radians(azimuthDegrees);
    const glm::vec3 wsToSun(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
    Light sun = makeDirectionalLight(-wsToSun, 3.0f, {1.0f, 0.96f, 0.9f});
    sun.name = "sun";
    sun.shadows = LightShadows::Soft;
    return sun;
}

inline void setCamera(SceneBuilder& builder, glm::vec3 wsEye, glm::vec3 wsTarget, float yfovDegrees) {
    Camera camera = makeLookAtCamera(wsEye, wsTarget, glm::radians(yfovDegrees));
    camera.name = "camera";
    builder.setCamera(camera);
}

// A square ground of side `size` centred at (0, 0, zCentre), receiving and casting shadows.
inline void addGround(SceneBuilder& builder, float size, float zCentre = 0.0f) {
    const uint32_t gray = builder.addMaterial(colored("ground", glm::vec3(0.6f)));
    builder.addInstance(builder.addMesh(makePlaneMesh({size, size}, gray, size / 2.0f)), at({0, 0, zCentre}), true,
                        "ground");
}

inline uint32_t addBox(SceneBuilder& builder, glm::vec3 halfExtents, uint32_t material, const glm::mat4& pose,
                       const std::string& name) {
    return builder.addInstance(builder.addMesh(makeBoxMesh(halfExtents, material)), pose, true, name);
}

inline uint32_t addPole(SceneBuilder& builder, float radius, float height, uint32_t material, glm::vec3 wsBase,
                        const std::string& name) {
    return builder.addInstance(builder.addMesh(makeCylinderMesh(radius, height, material, 16)), at(wsBase), true, name);
}

inline uint32_t addSphere(SceneBuilder& builder, float radius, uint32_t material, glm::vec3 wsCentre,
                          const std::string& name) {
    return builder.addInstance(builder.addMesh(makeSphereMesh(radius, material, 32, 16)), at(wsCentre), true, name);
}

// The scenes added for the shadow-fidelity measurements (canonical_scenes_more.cpp, docs/fidelity.md).
Scene makeFarField();
Scene makeThinSlabs();
Scene makeGrazingSun();
Scene makeFence();
Scene makeFieldOfObjects();
Scene makeCube();
Scene makeCadEngine();
Scene makeSpotShelf();
Scene makePcssContact();
Scene makeRoomCorner();

}  // namespace penumbra::canonical
