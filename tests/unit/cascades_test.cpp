#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/cascades.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

// The 8 world-space corners of the camera frustum between view depths d0 and d1.
std::vector<glm::vec3> sliceCorners(const CameraView& camera, float d0, float d1) {
    const float ty = std::tan(0.5f * camera.yfov), tx = ty * camera.aspect;
    std::vector<glm::vec3> corners;
    for (float d : {d0, d1}) {
        for (float sx : {-1.0f, 1.0f}) {
            for (float sy : {-1.0f, 1.0f}) {
                corners.push_back(glm::vec3(camera.worldFromView * glm::vec4(sx * tx * d, sy * ty * d, -d, 1.0f)));
            }
        }
    }
    return corners;
}

}  // namespace

TEST(CascadeSplits, AreRatiosTimesTheShadowDistanceWithTheLastAtTheFullDistance) {
    const CameraView camera = cameraLookingAt({0, 0, 0}, {0, 0, -1});
    const std::vector<float> splits = cascadeSplitDistances(camera, 100.0f, 4, {0.1f, 0.25f, 0.5f});
    ASSERT_EQ(splits.size(), 4u);
    EXPECT_FLOAT_EQ(splits[0], 10.0f);
    EXPECT_FLOAT_EQ(splits[1], 25.0f);
    EXPECT_FLOAT_EQ(splits[2], 50.0f);
    EXPECT_FLOAT_EQ(splits[3], 100.0f);
}

TEST(CascadeSplits, LogSplitsGrowGeometricallyOverTheRange) {
    const CameraView camera = cameraLookingAt({0, 2, 0}, {0, 2, -1});
    DirectionalShadowSettings settings;
    settings.cascadeSplits = CascadeSplitMode::Log;
    const std::vector<float> splits = cascadeSplitDistances(camera, 1.0f, 81.0f, settings, 100.0f);
    ASSERT_EQ(splits.size(), 4u);
    EXPECT_NEAR(splits[0], 3.0f, 1e-4f);  // 1 * 81^(1/4)
    EXPECT_NEAR(splits[1], 9.0f, 1e-4f);
    EXPECT_NEAR(splits[2], 27.0f, 1e-3f);
    EXPECT_FLOAT_EQ(splits[3], 81.0f);
}

TEST(CascadeSplits, PracticalSplitsBlendLogAndUniformByLambda) {
    const CameraView camera = cameraLookingAt({0, 2, 0}, {0, 2, -1});
    DirectionalShadowSettings settings;
    settings.cascadeSplits = CascadeSplitMode::Practical;
    settings.splitLambda = 0.25f;
    const std::vector<float> splits = cascadeSplitDistances(camera, 1.0f, 81.0f, settings, 100.0f);
    EXPECT_NEAR(splits[0], 0.25f * 3.0f + 0.75f * 21.0f, 1e-3f);
    EXPECT_NEAR(splits[1], 0.25f * 9.0f + 0.75f * 41.0f, 1e-3f);
}

TEST(CascadeSplits, ManualSplitsKeepTheRatiosAndEndAtTheRangesFarEnd) {
    const CameraView camera = cameraLookingAt({0, 2, 0}, {0, 2, -1});
    DirectionalShadowSettings settings;
    settings.cascadeSplits = CascadeSplitMode::Manual;
    const std::vector<float> splits = cascadeSplitDistances(camera, 1.0f, 30.0f, settings, 100.0f);
    EXPECT_EQ(splits, (std::vector<float>{10.0f, 25.0f, 30.0f, 30.0f}));
}

TEST(TightFit, HalfSizesRoundUpToAnEighthOfAnOctave) {
    EXPECT_FLOAT_EQ(quantizedHalfExtent(8.0f), 8.0f);
    EXPECT_NEAR(quantizedHalfExtent(8.1f), 8.0f * std::exp2(0.125f), 1e-4f);
    EXPECT_EQ(quantizedHalfExtent(8.2f), quantizedHalfExtent(8.6f));  // small changes keep the texel size
}

TEST(TightFit, BoxHoldsTheBoundsWithTheMarginAndSnapsToWholeTexels) {
    const glm::mat4 rotation = lightRotationFromWorld(glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f)));
    const Aabb rsBounds{{-3.2f, 1.1f, -7.0f}, {2.9f, 4.0f, 2.0f}};
    const CascadeLightView view = fitTightLightView(rotation, rsBounds, 512, 6.0f);
    // Every corner of the bounds lies inside the ortho box by at least the 6-texel margin.
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 rs((i & 1) ? rsBounds.max.x : rsBounds.min.x, (i & 2) ? rsBounds.max.y : rsBounds.min.y,
                           (i & 4) ? rsBounds.max.z : rsBounds.min.z);
        const glm::vec3 ls = glm::vec3(view.lightFromWorld * glm::inverse(rotation) * glm::vec4(rs, 1.0f));
        EXPECT_LE(std::abs(ls.x), view.halfExtent - 6.0f * view.wsTexelSize + 1e-4f);
        EXPECT_LE(std::abs(ls.y), view.halfExtent - 6.0f * view.wsTexelSize + 1e-4f);
        EXPECT_LE(ls.z, view.receiversNear + 1e-4f);
        EXPECT_GE(ls.z, -view.receiversFar - 1e-4f);
    }
    EXPECT_LT(view.halfExtent, 3.05f / (1.0f - 12.0f / 512.0f) * std::exp2(0.125f));  // no bigger than needed
    // The origin of the light view sits on a whole texel of the rotation space.
    const glm::vec3 translation(view.lightFromWorld[3]);
    EXPECT_NEAR(translation.x / view.wsTexelSize, std::round(translation.x / view.wsTexelSize), 1e-3f);
    EXPECT_NEAR(translation.y / view.wsTexelSize, std::round(translation.y / view.wsTexelSize), 1e-3f);
}

TEST(CascadeSplits, ShadowDistanceIsLimitedByTheCameraFarPlane) {
    EXPECT_FLOAT_EQ(shadowDistance(cameraLookingAt({0, 0, 0}, {0, 0, -1}, 40.0f), 100.0f), 40.0f);
    EXPECT_FLOAT_EQ(shadowDistance(cameraLookingAt({0, 0, 0}, {0, 0, -1}, INFINITY), 100.0f), 100.0f);
}

TEST(CascadeSplits, DecreasingRatiosNeverInvertASlice) {
    const CameraView camera = cameraLookingAt({0, 0, 0}, {0, 0, -1});
    const std::vector<float> splits = cascadeSplitDistances(camera, 100.0f, 4, {0.5f, 0.2f, 0.1f});
    EXPECT_FLOAT_EQ(splits[1], 50.0f);
    EXPECT_FLOAT_EQ(splits[2], 50.0f);
}

TEST(CullingSphere, EnclosesTheFrustumSliceAndTouchesItsFarCorners) {
    const CameraView camera = cameraLookingAt({1, 2, 3}, {4, 0, -5}, 1000.0f, 160, 90);
    for (auto [d0, d1] : {std::pair{0.1f, 10.0f}, std::pair{10.0f, 25.0f}, std::pair{50.0f, 100.0f}}) {
        const CascadeSphere sphere = frustumSliceSphere(camera, d0, d1);
        float farthest = 0.0f;
        for (const glm::vec3& corner : sliceCorners(camera, d0, d1)) {
            farthest = std::max(farthest, glm::distance(corner, sphere.wsCenter));
        }
        EXPECT_NEAR(farthest, sphere.radius, 1e-3f * sphere.radius) << d0 << ".." << d1;
    }
}

TEST(CullingSphere, IsMinimalForAThinSlice) {
    // A narrow view and a thin far slice: both rings lie on the sphere, so the far ring's circle alone
    // would miss the near corners.
    Camera narrow;
    narrow.yfov = glm::radians(10.0f);
    const CameraView camera = makeCameraView(narrow, 100, 100);
    const CascadeSphere sphere = frustumSliceSphere(camera, 50.0f, 60.0f);
    for (const glm::vec3& corner : sliceCorners(camera, 50.0f, 60.0f)) {
        EXPECT_NEAR(glm::distance(corner, sphere.wsCenter), sphere.radius, 1e-3f);
    }
}

TEST(CullingSphere, RadiusIsInvariantUnderCameraRotation) {
    const CascadeSphere a = frustumSliceSphere(cameraLookingAt({0, 1, 0}, {0, 1, -1}, 1000.0f, 160, 90), 10.0f, 25.0f);
    const CascadeSphere b = frustumSliceSphere(cameraLookingAt({0, 1, 0}, {3, -2, 1}, 1000.0f, 160, 90), 10.0f, 25.0f);
    EXPECT_FLOAT_EQ(a.radius, b.radius);
    EXPECT_GT(glm::distance(a.wsCenter, b.wsCenter), 1.0f);
}

TEST(CullingSphere, IsIndependentOfTheLight) {
    Scene scene;  // no light enters computeCascadeSpheres at all: only camera and settings
    const CameraView camera = cameraLookingAt({0, 5, 10}, {0, 0, 0});
    const std::vector<CascadeSphere> spheres = computeCascadeSpheres(camera, sphereCascadeSettings());
    ASSERT_EQ(spheres.size(), 4u);
    EXPECT_FLOAT_EQ(spheres[1].vsNear, 10.0f);
    EXPECT_FLOAT_EQ(spheres[1].vsFar, 25.0f);
}

TEST(LightView, LooksAlongTheLightDirection) {
    const glm::vec3 direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const glm::mat4 rotation = lightRotationFromWorld(direction);
    const glm::vec3 lsDirection = glm::vec3(rotation * glm::vec4(direction, 0.0f));
    EXPECT_NEAR(lsDirection.z, -1.0f, 1e-5f);
    EXPECT_NEAR(glm::determinant(glm::mat3(rotation)), 1.0f, 1e-5f);
}

TEST(LightView, OrthoProjectionUsesStandardDepthAndVulkanYDown) {
    const glm::mat4 clip = orthoClipFromLight(10.0f, 30.0f, 10.0f);
    EXPECT_NEAR((clip * glm::vec4(0, 0, 30, 1)).z, 0.0f, 1e-6f);   // near plane, toward the light
    EXPECT_NEAR((clip * glm::vec4(0, 0, -10, 1)).z, 1.0f, 1e-6f);  // far plane
    EXPECT_NEAR((clip * glm::vec4(10, 10, 0, 1)).x, 1.0f, 1e-6f);
    EXPECT_NEAR((clip * glm::vec4(10, 10, 0, 1)).y, -1.0f, 1e-6f);  // light-space up = top of the tile
}

TEST(TexelSnapping, MovingTheCameraMovesShadowTexelsByWholeTexelsOnly) {
    const glm::mat4 rotation = lightRotationFromWorld(glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f)));
    const uint32_t tileSize = 512;
    const glm::vec3 wsPoint(1.37f, 0.25f, -6.81f);
    auto texelOf = [&](glm::vec3 eye) {
        const CameraView camera = cameraLookingAt(eye, eye + glm::vec3(0, -0.3f, -1));
        const CascadeLightView view = fitCascadeLightView(rotation, frustumSliceSphere(camera, 0.1f, 10.0f), tileSize);
        return glm::vec2(view.lightFromWorld * glm::vec4(wsPoint, 1.0f)) / view.wsTexelSize;
    };
    const glm::vec2 before = texelOf({0, 2, 0});
    for (float step : {0.013f, 0.071f, 0.29f, 1.7f}) {
        const glm::vec2 moved = texelOf({step, 2.0f + 0.5f * step, -step}) - before;
        EXPECT_NEAR(moved.x, std::round(moved.x), 2e-3f) << step;
        EXPECT_NEAR(moved.y, std::round(moved.y), 2e-3f) << step;
    }
}

TEST(TexelSnapping, KeepsTheSphereCentreWithinHalfATexelOfTheTileCentre) {
    const glm::mat4 rotation = lightRotationFromWorld(glm::vec3(0.0f, -1.0f, 0.0f));
    CascadeSphere sphere;
    sphere.wsCenter = glm::vec3(3.123f, 0.0f, -7.77f);
    sphere.radius = 8.0f;
    const CascadeLightView view = fitCascadeLightView(rotation, sphere, 256);
    EXPECT_FLOAT_EQ(view.wsTexelSize, 16.0f / 256.0f);
    EXPECT_LE(std::abs(view.lsSphereCenter.x), 0.5f * view.wsTexelSize + 1e-5f);
    EXPECT_LE(std::abs(view.lsSphereCenter.y), 0.5f * view.wsTexelSize + 1e-5f);
    EXPECT_NEAR(glm::vec3(view.lightFromWorld * glm::vec4(sphere.wsCenter, 1.0f)).x, view.lsSphereCenter.x, 1e-5f);
}
