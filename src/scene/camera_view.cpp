#include "penumbra/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_validation.h"

namespace penumbra {

glm::mat4 reversedZPerspective(float yfov, float aspect, float zNear, float zFar) {
    const float f = 1.0f / std::tan(0.5f * yfov);
    glm::mat4 m(0.0f);
    m[0][0] = f / aspect;
    m[1][1] = -f;  // Vulkan clip y points down
    m[2][3] = -1.0f;
    if (std::isinf(zFar)) {
        m[3][2] = zNear;  // depth = zNear / -zView
    } else {
        m[2][2] = zNear / (zFar - zNear);
        m[3][2] = zNear * zFar / (zFar - zNear);
    }
    return m;
}

CameraView makeCameraView(const Camera& camera, uint32_t width, uint32_t height) {
    validateCamera(camera, "camera" + (camera.name.empty() ? std::string() : " '" + camera.name + "'"));
    CameraView view;
    view.width = std::max(1u, width);
    view.height = std::max(1u, height);
    view.aspect = float(view.width) / float(view.height);
    view.yfov = camera.yfov;
    view.zNear = camera.zNear;
    view.zFar = camera.zFar;
    // Strip any scale from the node transform: only position and orientation define the view.
    const glm::mat4& m = camera.worldFromView;
    glm::mat4 rigid(1.0f);
    rigid[0] = glm::vec4(glm::normalize(glm::vec3(m[0])), 0.0f);
    rigid[1] = glm::vec4(glm::normalize(glm::vec3(m[1])), 0.0f);
    rigid[2] = glm::vec4(glm::normalize(glm::vec3(m[2])), 0.0f);
    rigid[3] = m[3];
    view.worldFromView = rigid;
    view.viewFromWorld = glm::inverse(rigid);
    view.clipFromView = reversedZPerspective(view.yfov, view.aspect, view.zNear, view.zFar);
    view.clipFromWorld = view.clipFromView * view.viewFromWorld;
    view.wsPosition = glm::vec3(rigid[3]);
    view.wsForward = -glm::vec3(rigid[2]);
    return view;
}

CameraView translatedCameraView(const CameraView& view, const glm::vec3& wsOffset) {
    CameraView moved = view;
    moved.worldFromView[3] += glm::vec4(wsOffset, 0.0f);
    moved.viewFromWorld = glm::inverse(moved.worldFromView);
    moved.clipFromWorld = moved.clipFromView * moved.viewFromWorld;
    moved.wsPosition = glm::vec3(moved.worldFromView[3]);
    return moved;
}

glm::vec3 wsCameraRight(const CameraView& view) { return glm::normalize(glm::vec3(view.worldFromView[0])); }

Camera autoFramingCamera(const Aabb& wsBounds) {
    Camera camera;
    camera.name = "auto";
    const glm::vec3 center = wsBounds.valid() ? wsBounds.center() : glm::vec3(0.0f);
    const float radius = wsBounds.valid() ? std::max(0.5f * glm::length(wsBounds.extent()), 1e-3f) : 1.0f;
    camera.yfov = glm::radians(45.0f);
    const float distance = radius / std::sin(0.5f * camera.yfov) * 1.05f;
    const glm::vec3 wsDirection = glm::normalize(glm::vec3(0.6f, 0.5f, 1.0f));  // from the centre
    const glm::vec3 eye = center + wsDirection * distance;
    camera.worldFromView = glm::inverse(glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.zNear = std::max(1e-4f, (distance - radius) * 0.5f);
    camera.zFar = std::numeric_limits<float>::infinity();
    return camera;
}

CameraView resolveCameraView(const Scene& scene, uint32_t width, uint32_t height) {
    if (scene.camera) return makeCameraView(*scene.camera, width, height);
    return makeCameraView(autoFramingCamera(scene.wsBounds), width, height);
}

glm::vec3 wsRayDirection(const CameraView& view, float px, float py) {
    const float ndcX = 2.0f * px / float(view.width) - 1.0f;
    const float ndcY = 2.0f * py / float(view.height) - 1.0f;  // +1 at the bottom row
    const float tanHalf = std::tan(0.5f * view.yfov);
    const glm::vec3 vsDirection(ndcX * tanHalf * view.aspect, -ndcY * tanHalf, -1.0f);
    return glm::normalize(glm::vec3(view.worldFromView * glm::vec4(vsDirection, 0.0f)));
}

}  // namespace penumbra
