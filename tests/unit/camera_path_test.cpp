// penumbra-viewer's camera paths (src/viewer/camera_path.h): JSON round trip, bad input, interpolation
// and the scripted clock by frame index.
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "viewer/camera_path.h"

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

Camera lookingAt(glm::vec3 eye, glm::vec3 target, float yfov) {
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
    camera.yfov = yfov;
    camera.zNear = 0.25f;
    return camera;
}

CameraPath twoKeyframes() {
    CameraPath path;
    path.keyframes.push_back(keyframeOf(lookingAt({0, 1, 5}, {0, 0, 0}, 0.8f), 1.0f));
    path.keyframes.push_back(keyframeOf(lookingAt({5, 1, 0}, {0, 0, 0}, 0.6f), 3.0f));
    return path;
}

void expectSameMatrix(const glm::mat4& a, const glm::mat4& b, float tolerance = 1e-5f) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << c << "," << r;
}

std::string errorOf(const std::string& json) {
    try {
        parseCameraPath(json, "p.json");
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST(CameraPath, KeyframesRoundTripThroughJson) {
    const CameraPath path = twoKeyframes();
    const CameraPath back = parseCameraPath(cameraPathToJson(path), "p.json");
    ASSERT_EQ(back.keyframes.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back.keyframes[i].time, path.keyframes[i].time);
        EXPECT_EQ(back.keyframes[i].wsPosition, path.keyframes[i].wsPosition);
        EXPECT_EQ(back.keyframes[i].yfov, path.keyframes[i].yfov);
        EXPECT_NEAR(std::abs(glm::dot(back.keyframes[i].rotation, path.keyframes[i].rotation)), 1.0f, 1e-6f);
    }
    EXPECT_FLOAT_EQ(back.duration(), 2.0f);
}

TEST(CameraPath, KeyframeTimesGiveTheirCamerasAndTheEndsHold) {
    const CameraPath path = twoKeyframes();
    const Camera base = lookingAt({9, 9, 9}, {0, 0, 0}, 1.0f);
    const Camera first = lookingAt({0, 1, 5}, {0, 0, 0}, 0.8f), last = lookingAt({5, 1, 0}, {0, 0, 0}, 0.6f);
    expectSameMatrix(cameraOnPath(path, 1.0f, base).worldFromView, first.worldFromView);
    expectSameMatrix(cameraOnPath(path, 0.0f, base).worldFromView, first.worldFromView);  // before the start
    expectSameMatrix(cameraOnPath(path, 3.0f, base).worldFromView, last.worldFromView);
    expectSameMatrix(cameraOnPath(path, 9.0f, base).worldFromView, last.worldFromView);  // after the end
    EXPECT_FLOAT_EQ(cameraOnPath(path, 3.0f, base).yfov, 0.6f);
    EXPECT_EQ(cameraOnPath(path, 2.0f, base).zNear, base.zNear);  // projection limits from the base camera
}

TEST(CameraPath, MidpointInterpolatesPositionRotationAndFieldOfView) {
    const Camera middle = cameraOnPath(twoKeyframes(), 2.0f, Camera{});
    EXPECT_NEAR(middle.worldFromView[3].x, 2.5f, 1e-5f);
    EXPECT_NEAR(middle.worldFromView[3].z, 2.5f, 1e-5f);
    EXPECT_NEAR(middle.yfov, 0.7f, 1e-6f);
    // Halfway between looking along -Z and along -X (both toward the origin, slightly down): along -X-Z.
    const glm::vec3 forward = -glm::vec3(middle.worldFromView[2]);
    EXPECT_NEAR(forward.x, forward.z, 1e-4f);
    EXPECT_LT(forward.x, 0.0f);
}

TEST(CameraPath, ScriptedFramesSpreadOverThePathAndEndOnItsLastKeyframe) {
    const CameraPath path = twoKeyframes();
    EXPECT_FLOAT_EQ(scriptedPathTime(path, 0, 5), 1.0f);
    EXPECT_FLOAT_EQ(scriptedPathTime(path, 2, 5), 2.0f);
    EXPECT_FLOAT_EQ(scriptedPathTime(path, 4, 5), 3.0f);
    EXPECT_FLOAT_EQ(scriptedPathTime(path, 0, 1), 3.0f);  // one frame: the end
}

TEST(CameraPath, BadInputIsOneLineNamingTheField) {
    EXPECT_NE(errorOf("{").find("camera path p.json is not valid JSON"), std::string::npos);
    EXPECT_NE(errorOf("[]").find("an array \"keyframes\""), std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": []})").find("\"keyframes\" is empty"), std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": [{"position": [0,0,0], "rotation": [0,0,0,1]}]})").find("keyframes[0].time"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": [{"time": 0, "position": [0,0], "rotation": [0,0,0,1]}]})")
                  .find("keyframes[0].position must be an array of 3 numbers"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": [{"time": 0, "position": [0,0,0], "rotation": [0,0,0,0]}]})")
                  .find("non-zero quaternion"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": [{"time": 1, "position": [0,0,0], "rotation": [0,0,0,1]},
                                        {"time": 1, "position": [0,0,0], "rotation": [0,0,0,1]}]})")
                  .find("keyframes[1].time must be greater"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"keyframes": [{"time": 0, "position": [0,0,0], "rotation": [0,0,0,1], "yfov": 4}]})")
                  .find("yfov"),
              std::string::npos);
    for (const std::string& message : {errorOf("{"), errorOf(R"({"keyframes": 3})")})
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(CameraPath, JsonNestingHundredsOfThousandsDeepIsAnErrorNotAStackOverflow) {
    const std::string deep = "{\"keyframes\":[" + std::string(200000, '[') + std::string(200000, ']') + "]}";
    EXPECT_THROW(parseCameraPath(deep, "deep.json"), Error);
}
