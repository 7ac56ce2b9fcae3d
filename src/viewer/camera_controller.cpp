#include "viewer/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::viewer {

namespace {

constexpr float kRadiansPerPixel = 0.004f;
constexpr float kMaxPitch = 1.55f;  // just short of straight up or down
constexpr float kFastFactor = 4.0f;
constexpr float kWheelStep = 1.25f;  // speed factor per wheel tick

float sceneRadius(const Aabb& bounds) {
    const float radius = 0.5f * glm::length(bounds.max - bounds.min);
    return std::isfinite(radius) && radius > 1e-4f ? radius : 1.0f;
}

}  // namespace

CameraController::CameraController(const Camera& start, const Aabb& wsSceneBounds) : bounds_(wsSceneBounds) {
    reset(start);
}

void CameraController::reset(const Camera& start) {
    camera_ = start;
    mode_ = CameraMode::Fly;
    const glm::vec3 wsForward = -glm::normalize(glm::vec3(camera_.worldFromView[2]));
    yaw_ = std::atan2(-wsForward.x, -wsForward.z);
    pitch_ = std::asin(std::clamp(wsForward.y, -1.0f, 1.0f));
    speed_ = 0.5f * sceneRadius(bounds_);
    wsOrbitTarget = 0.5f * (bounds_.min + bounds_.max);
    orbitDistance_ = glm::length(wsPosition() - wsOrbitTarget);
}

// The view's rotation from yaw and pitch; the position stays.
void CameraController::lookFromAngles() {
    const glm::vec3 wsPosition = this->wsPosition();
    glm::mat4 worldFromView = glm::rotate(glm::mat4(1.0f), yaw_, glm::vec3(0, 1, 0));
    worldFromView = glm::rotate(worldFromView, pitch_, glm::vec3(1, 0, 0));
    worldFromView[3] = glm::vec4(wsPosition, 1.0f);
    camera_.worldFromView = worldFromView;
}

void CameraController::orbitToMatrix() {
    const glm::vec3 wsBackward{std::sin(yaw_) * std::cos(pitch_), -std::sin(pitch_), std::cos(yaw_) * std::cos(pitch_)};
    camera_.worldFromView[3] = glm::vec4(wsOrbitTarget + orbitDistance_ * wsBackward, 1.0f);
    lookFromAngles();
}

void CameraController::setMode(CameraMode mode) {
    if (mode == CameraMode::Orbit && mode_ != CameraMode::Orbit)
        orbitDistance_ = std::max(glm::length(wsPosition() - wsOrbitTarget), 1e-3f);
    mode_ = mode;
    if (mode_ == CameraMode::Orbit) orbitToMatrix();
}

void CameraController::frameScene() {
    wsOrbitTarget = 0.5f * (bounds_.min + bounds_.max);
    orbitDistance_ = 1.1f * sceneRadius(bounds_) / std::sin(0.5f * camera_.yfov);
    mode_ = CameraMode::Orbit;
    orbitToMatrix();
}

void CameraController::update(const CameraInput& input, float seconds) {
    if (input.wheel != 0.0f) {
        if (mode_ == CameraMode::Orbit)
            orbitDistance_ = std::max(orbitDistance_ * std::pow(kWheelStep, -input.wheel), 1e-3f);
        else
            speed_ = std::clamp(speed_ * std::pow(kWheelStep, input.wheel), 1e-3f, 1e6f);
    }
    const bool turned = input.rotating && input.cursorDelta != glm::vec2(0.0f);
    if (turned) {
        yaw_ -= input.cursorDelta.x * kRadiansPerPixel;
        pitch_ = std::clamp(pitch_ - input.cursorDelta.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    }
    if (mode_ == CameraMode::Orbit) {
        if (input.panning && input.cursorDelta != glm::vec2(0.0f)) {
            const float metresPerPixel = orbitDistance_ * 0.002f;
            wsOrbitTarget += metresPerPixel * (-input.cursorDelta.x * glm::vec3(camera_.worldFromView[0]) +
                                               input.cursorDelta.y * glm::vec3(camera_.worldFromView[1]));
        }
        if (turned || input.wheel != 0.0f || input.panning) orbitToMatrix();
        return;
    }
    if (turned) lookFromAngles();
    const glm::vec3 wsRight = glm::vec3(camera_.worldFromView[0]);
    const glm::vec3 wsForward = -glm::vec3(camera_.worldFromView[2]);
    glm::vec3 wsMove{0.0f};
    wsMove += (float(input.forward) - float(input.back)) * wsForward;
    wsMove += (float(input.right) - float(input.left)) * wsRight;
    wsMove += (float(input.up) - float(input.down)) * glm::vec3(0, 1, 0);
    if (wsMove == glm::vec3(0.0f)) return;
    const float metres = speed_ * (input.fast ? kFastFactor : 1.0f) * seconds;
    camera_.worldFromView[3] += glm::vec4(metres * glm::normalize(wsMove), 0.0f);
}

}  // namespace penumbra::viewer
