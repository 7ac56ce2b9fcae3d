#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "penumbra/camera.h"

using namespace penumbra;

namespace {
Camera lookingAt(glm::vec3 eye, glm::vec3 target, float zFar) {
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
    camera.yfov = glm::radians(60.0f);
    camera.zNear = 0.5f;
    camera.zFar = zFar;
    return camera;
}

// Projects a world point to pixel coordinates with the rasterizer's matrices.
glm::vec3 toPixel(const CameraView& view, glm::vec3 wsPoint) {
    const glm::vec4 clip = view.clipFromWorld * glm::vec4(wsPoint, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * float(view.width), (ndc.y * 0.5f + 0.5f) * float(view.height), ndc.z};
}
}  // namespace

TEST(CameraView, ReversedZMapsNearPlaneToOneAndFarPlaneToZero) {
    const CameraView view = makeCameraView(lookingAt({0, 0, 0}, {0, 0, -1}, 100.0f), 64, 64);
    EXPECT_NEAR(toPixel(view, {0, 0, -0.5f}).z, 1.0f, 1e-5f);
    EXPECT_NEAR(toPixel(view, {0, 0, -100.0f}).z, 0.0f, 1e-5f);
}

TEST(CameraView, InfiniteFarPlaneKeepsDepthPositive) {
    const CameraView view = makeCameraView(lookingAt({0, 0, 0}, {0, 0, -1}, INFINITY), 64, 64);
    EXPECT_NEAR(toPixel(view, {0, 0, -0.5f}).z, 1.0f, 1e-5f);
    const float farDepth = toPixel(view, {0, 0, -1e5f}).z;
    EXPECT_GT(farDepth, 0.0f);
    EXPECT_LT(farDepth, 1e-5f);
}

TEST(CameraView, PixelCentreRayProjectsBackToThatPixelCentre) {
    const CameraView view = makeCameraView(lookingAt({3, 2, 5}, {0, 0, 0}, INFINITY), 160, 90);
    for (glm::vec2 px : {glm::vec2(0.5f, 0.5f), glm::vec2(159.5f, 0.5f), glm::vec2(80.5f, 44.5f), glm::vec2(10.5f, 89.5f)}) {
        const glm::vec3 wsPoint = view.wsPosition + 7.0f * wsRayDirection(view, px.x, px.y);
        const glm::vec3 back = toPixel(view, wsPoint);
        EXPECT_NEAR(back.x, px.x, 1e-3f);
        EXPECT_NEAR(back.y, px.y, 1e-3f);
    }
}

TEST(CameraView, TopRowOfPixelsLooksUp) {
    const CameraView view = makeCameraView(lookingAt({0, 0, 0}, {0, 0, -1}, INFINITY), 64, 64);
    EXPECT_GT(wsRayDirection(view, 32, 0.5f).y, 0.0f);
    EXPECT_LT(wsRayDirection(view, 32, 63.5f).y, 0.0f);
}

TEST(CameraView, AutoFramingSeesTheWholeBounds) {
    Aabb bounds;
    bounds.extend({-10, 0, -4});
    bounds.extend({6, 3, 8});
    const CameraView view = makeCameraView(autoFramingCamera(bounds), 100, 100);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 px = toPixel(view, corner);
        EXPECT_GE(px.x, 0.0f);
        EXPECT_LE(px.x, 100.0f);
        EXPECT_GE(px.y, 0.0f);
        EXPECT_LE(px.y, 100.0f);
        EXPECT_GT(px.z, 0.0f);
    }
}
