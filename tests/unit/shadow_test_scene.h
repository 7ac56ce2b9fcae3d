#pragma once
// In-memory scenes for the shadow planner tests: boxes (bounds only, no vertices), lights, cameras, and
// the depth a view has of the ground plane.
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/camera.h"
#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "penumbra/shadow_settings.h"
#include "shadows/shadow_planner.h"

namespace penumbra::shadow_test {

// A scene with one default material (shadows On) and one mesh using it, plus a second material with
// shadows Off and a mesh using that (mesh 1).
inline Scene baseScene() {
    Scene scene;
    scene.materials.resize(2);
    scene.materials[1].shadows = MaterialShadowMode::Off;
    scene.meshes.resize(2);
    scene.meshes[0].materialIndex = 0;
    scene.meshes[1].materialIndex = 1;
    return scene;
}

inline uint32_t addBox(Scene& scene, glm::vec3 wsMin, glm::vec3 wsMax, bool castShadows = true, uint32_t mesh = 0) {
    Instance instance;
    instance.meshIndex = mesh;
    instance.castShadows = castShadows;
    instance.wsBounds.extend(wsMin);
    instance.wsBounds.extend(wsMax);
    scene.instances.push_back(instance);
    scene.wsBounds.extend(instance.wsBounds);
    return uint32_t(scene.instances.size() - 1);
}

inline uint32_t addDirectionalLight(Scene& scene, glm::vec3 wsDirection, float strength = 1.0f,
                                    LightShadows shadows = LightShadows::Soft) {
    Light light;
    light.type = LightType::Directional;
    light.wsDirection = glm::normalize(wsDirection);
    light.shadowStrength = strength;
    light.shadows = shadows;
    scene.lights.push_back(light);
    return uint32_t(scene.lights.size() - 1);
}

// Shadow settings with sphere-fitted cascades (culling spheres, manual ratios, as Catlike Coding "Directional
// Shadows"), which most planner tests check; the tight fit and log splits (the defaults) have their own
// tests.
inline ShadowSettings sphereCascadeSettings() {
    ShadowSettings settings;
    settings.directional.fit = CascadeFit::Sphere;
    settings.directional.cascadeSplits = CascadeSplitMode::Manual;
    return settings;
}

inline CameraView cameraLookingAt(glm::vec3 eye, glm::vec3 target, float zFar = 1000.0f, uint32_t width = 64,
                                  uint32_t height = 64) {
    Camera camera;
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 up = std::abs(forward.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, up));
    camera.yfov = glm::radians(60.0f);
    camera.zNear = 0.1f;
    camera.zFar = zFar;
    return makeCameraView(camera, width, height);
}

// The plan of a 40 m ground with a box on it under one sun, with `cascades` cascades (sphere-fitted,
// 40 m shadow distance), seen from (0, 6, 15).
inline ShadowFrame groundAndBoxPlan(uint32_t cascades) {
    Scene scene = baseScene();
    addBox(scene, {-20, -1, -20}, {20, 0, 20});
    addBox(scene, {-1, 0, -1}, {1, 2, 1});
    addDirectionalLight(scene, {0.3f, -1, 0.2f});
    ShadowSettings settings = sphereCascadeSettings();
    settings.maxDistance = 40.0f;
    settings.directional.cascadeCount = cascades;
    return ShadowPlanner::plan(scene, cameraLookingAt({0, 6, 15}, {0, 0, 0}), settings);
}

// The reversed-Z depth image of the ground plane y = 0 (up to 60 m) seen by `view`; 0 elsewhere.
inline Image groundDepth(const CameraView& view) {
    Image depth(view.width, view.height, 4, 0);
    for (uint32_t y = 0; y < view.height; ++y)
        for (uint32_t x = 0; x < view.width; ++x) {
            const glm::vec3 dir = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            if (dir.y >= -1e-4f) continue;
            const glm::vec3 p = view.wsPosition + dir * (-view.wsPosition.y / dir.y);
            if (glm::length(p - view.wsPosition) > 60.0f) continue;
            const glm::vec4 clip = view.clipFromWorld * glm::vec4(p, 1.0f);
            const float d = clip.z / clip.w;
            std::memcpy(&depth.pixels[(size_t(y) * view.width + x) * 4], &d, sizeof(float));
        }
    return depth;
}

}  // namespace penumbra::shadow_test
