// penumbra-viewer's camera (src/viewer/camera_controller.cpp): it starts exactly at the scene's camera,
// flies along its own axes, and the orbit camera frames the scene.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "viewer/camera_controller.h"

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

Aabb unitBox() {
    Aabb box;
    box.extend(glm::vec3(-1.0f));
    box.extend(glm::vec3(1.0f));
    return box;
}

Camera lookingAtOrigin() {
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(glm::vec3(3, 2, 5), glm::vec3(0), glm::vec3(0, 1, 0)));
    return camera;
}

}  // namespace

TEST(ViewerCamera, StartsExactlyAtTheScenesCamera) {
    const Camera start = lookingAtOrigin();
    CameraController controller(start, unitBox());
    controller.update(CameraInput{}, 0.016f);
    EXPECT_EQ(controller.camera().worldFromView, start.worldFromView);
}

TEST(ViewerCamera, ForwardFliesAlongTheViewDirectionAtTheSpeed) {
    const Camera start = lookingAtOrigin();
    CameraController controller(start, unitBox());
    CameraInput input;
    input.forward = true;
    controller.update(input, 1.0f);
    const glm::vec3 wsForward = -glm::vec3(start.worldFromView[2]);
    const glm::vec3 moved = controller.wsPosition() - glm::vec3(start.worldFromView[3]);
    EXPECT_NEAR(glm::length(moved), controller.speed(), 1e-4f);
    EXPECT_NEAR(glm::dot(glm::normalize(moved), wsForward), 1.0f, 1e-5f);
    input.fast = true;
    const glm::vec3 before = controller.wsPosition();
    controller.update(input, 1.0f);
    EXPECT_NEAR(glm::length(controller.wsPosition() - before), 4.0f * controller.speed(), 1e-3f);
}

TEST(ViewerCamera, WheelChangesTheFlySpeed) {
    CameraController controller(lookingAtOrigin(), unitBox());
    const float speed = controller.speed();
    CameraInput input;
    input.wheel = 2.0f;
    controller.update(input, 0.0f);
    EXPECT_GT(controller.speed(), speed * 1.5f);
}

TEST(ViewerCamera, FramingTheSceneLooksAtItsCentreFromOutsideIt) {
    CameraController controller(lookingAtOrigin(), unitBox());
    controller.frameScene();
    EXPECT_EQ(controller.mode(), CameraMode::Orbit);
    const glm::vec3 wsForward = -glm::vec3(controller.camera().worldFromView[2]);
    EXPECT_NEAR(glm::dot(wsForward, glm::normalize(-controller.wsPosition())), 1.0f, 1e-4f);
    EXPECT_GT(glm::length(controller.wsPosition()), glm::sqrt(3.0f));
    CameraInput input;
    input.rotating = true;
    input.cursorDelta = glm::vec2(100.0f, 0.0f);
    const float distance = glm::length(controller.wsPosition());
    controller.update(input, 0.016f);
    EXPECT_NEAR(glm::length(controller.wsPosition()), distance, 1e-3f);  // orbiting keeps the distance
}
