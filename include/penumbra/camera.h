#pragma once
// The camera resolved for an output size: the one convention that the rasterizer and the ray-traced
// reference share. View space is right-handed, the camera looks along -Z with +Y up. Clip space is
// Vulkan's (y down, pixel (0,0) top-left) with reversed Z: depth 1 at the near plane, 0 at the far
// plane (or at infinity). Pixel (x, y) is sampled at its centre (x + 0.5, y + 0.5).
#include <cstdint>

#include <glm/glm.hpp>

#include <penumbra/scene.h>

namespace penumbra {

struct CameraView {
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 worldFromView{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::mat4 clipFromWorld{1.0f};
    glm::vec3 wsPosition{0.0f};
    glm::vec3 wsForward{0.0f, 0.0f, -1.0f};
    float yfov = 0.8f;
    float aspect = 1.0f;
    float zNear = 0.1f;
    float zFar = 0.0f;  // may be +infinity
    uint32_t width = 1;
    uint32_t height = 1;
};

// Reversed-Z perspective for Vulkan clip space; zFar may be +infinity.
glm::mat4 reversedZPerspective(float yfov, float aspect, float zNear, float zFar);

// The scene's camera (docs/scene-format.md: node named "camera", else the first camera, else an automatic
// framing of the scene bounds) for an output of width x height pixels.
CameraView resolveCameraView(const Scene& scene, uint32_t width, uint32_t height);
CameraView makeCameraView(const Camera& camera, uint32_t width, uint32_t height);
// The same view with the camera moved by wsOffset (orientation, projection and size unchanged); the
// shimmer measurement moves it 2 cm to its right (penumbra compare --shimmer).
CameraView translatedCameraView(const CameraView& view, const glm::vec3& wsOffset);
// The camera's right axis (+X of view space) in world space, unit.
glm::vec3 wsCameraRight(const CameraView& view);
// A camera that frames `wsBounds` from above and in front; used when a scene has no camera.
Camera autoFramingCamera(const Aabb& wsBounds);

// Unit world-space direction of the primary ray through the point (px, py) in pixel coordinates
// (pixel centres are at half-integers).
glm::vec3 wsRayDirection(const CameraView& view, float px, float py);

}  // namespace penumbra
