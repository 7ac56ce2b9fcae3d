#pragma once
// A recorded camera path of penumbra-viewer (--camera-path plays one, P / --record-camera-path records
// one): keyframes of time, position, rotation and vertical field of view, as JSON (docs/viewer.md "Camera paths").
// Pure CPU, no window, unit-tested.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "penumbra/scene.h"

namespace penumbra::viewer {

struct CameraKeyframe {
    float time = 0.0f;                   // seconds from the path's start, increasing
    glm::vec3 wsPosition{0.0f};
    glm::quat rotation{1, 0, 0, 0};      // worldFromView's rotation (the camera looks along -Z, +Y up)
    float yfov = 0.8f;                   // radians
};

struct CameraPath {
    std::vector<CameraKeyframe> keyframes;  // at least one when parsed

    float duration() const { return keyframes.empty() ? 0.0f : keyframes.back().time - keyframes.front().time; }
};

// Parses a path's JSON; throws penumbra::Error with one line naming `name` and the bad field.
CameraPath parseCameraPath(const std::string& json, const std::string& name);
CameraPath loadCameraPath(const std::string& path);
std::string cameraPathToJson(const CameraPath& path);
// Writes the JSON atomically; throws penumbra::Error on failure.
void saveCameraPath(const CameraPath& path, const std::string& file);

CameraKeyframe keyframeOf(const Camera& camera, float time);
// The camera at `time` seconds from the path's start (clamped to the path): position and field of view
// interpolated linearly, rotation spherically, between the keyframes around it; exactly a keyframe's
// camera at its time. zNear and zFar come from `base`.
Camera cameraOnPath(const CameraPath& path, float time, const Camera& base);
// Scripted playback (--screenshot FILE --frames N): frame i of N shows the path at i / (N - 1) of its
// duration, so the first frame is the first keyframe and the last frame (the screenshot) the last one,
// whatever the wall clock does.
float scriptedPathTime(const CameraPath& path, uint32_t frame, uint32_t frames);

}  // namespace penumbra::viewer
