// Perspective shadow matrices of spot lights and point-light faces.
#include <gtest/gtest.h>

#include <cmath>

#include "shadows/spot_projection.h"

using namespace penumbra;

TEST(SpotProjection, PerspectiveMatrixMatchesAHandComputation) {
    // tan(fov/2) = 0.5, near 1, far 10. Light-space point (1, 2, -4): distance d = 4,
    // ndc x = 1 / (4 * 0.5) = 0.5, ndc y = -2 / (4 * 0.5) = -1 (y down),
    // depth = far (d - near) / ((far - near) d) = 10 * 3 / (9 * 4) = 0.8333.
    const glm::vec4 clip = perspectiveClipFromLight(0.5f, 1.0f, 10.0f) * glm::vec4(1.0f, 2.0f, -4.0f, 1.0f);
    EXPECT_FLOAT_EQ(clip.w, 4.0f);
    EXPECT_FLOAT_EQ(clip.x / clip.w, 0.5f);
    EXPECT_FLOAT_EQ(clip.y / clip.w, -1.0f);
    EXPECT_NEAR(clip.z / clip.w, 30.0f / 36.0f, 1e-6f);
}

TEST(SpotProjection, DepthIsZeroAtTheNearPlaneAndOneAtTheFarPlane) {
    const glm::mat4 m = perspectiveClipFromLight(1.0f, 0.1f, 25.0f);
    const glm::vec4 near = m * glm::vec4(0.0f, 0.0f, -0.1f, 1.0f);
    const glm::vec4 far = m * glm::vec4(0.0f, 0.0f, -25.0f, 1.0f);
    EXPECT_NEAR(near.z / near.w, 0.0f, 1e-6f);
    EXPECT_NEAR(far.z / far.w, 1.0f, 1e-6f);
}

TEST(SpotProjection, LightViewPutsTheLightAtTheOriginLookingDownMinusZ) {
    const glm::vec3 position(3.0f, 4.0f, -2.0f);
    const glm::vec3 direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
    const glm::mat4 lightFromWorld = perspectiveLightFromWorld(position, direction);
    const glm::vec3 origin(lightFromWorld * glm::vec4(position, 1.0f));
    const glm::vec3 ahead(lightFromWorld * glm::vec4(position + 5.0f * direction, 1.0f));
    EXPECT_NEAR(glm::length(origin), 0.0f, 1e-5f);
    EXPECT_NEAR(ahead.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ahead.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ahead.z, -5.0f, 1e-5f);
}

TEST(SpotProjection, MarginWidensTheFrustumSoTheConeEndsMarginTexelsInsideTheTile) {
    const float tanHalf = tanHalfFovWithMargin(0.5f, 100, 10.0f);
    EXPECT_FLOAT_EQ(tanHalf, 0.5f * 100.0f / 80.0f);
    // The cone's edge lands at ndc 0.5 / tanHalf = 0.8, i.e. 10 texels from the tile's edge.
    EXPECT_FLOAT_EQ((1.0f - 0.5f / tanHalf) * 50.0f, 10.0f);
}

TEST(SpotProjection, EachPointLightFaceIsChosenByItsOwnDirection) {
    const auto& faces = pointLightFaceDirections();
    for (uint32_t face = 0; face < 6; ++face) {
        EXPECT_EQ(pointLightFaceOf(faces[face]), face);
        EXPECT_EQ(pointLightFaceOf(faces[face] * 3.0f + glm::vec3(0.4f, -0.3f, 0.2f)), face);
    }
}

TEST(SpotProjection, EveryDirectionProjectsInsideTheFaceThatMajorAxisPicks) {
    const glm::mat4 clipFromLight = perspectiveClipFromLight(1.0f, 0.1f, 10.0f);
    for (int i = 0; i < 200; ++i) {
        // Deterministic directions spread over the sphere (a spherical Fibonacci lattice).
        const float z = 1.0f - (float(i) + 0.5f) / 100.0f;
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = float(i) * 2.39996323f;
        const glm::vec3 direction(r * std::cos(phi), r * std::sin(phi), z);
        const uint32_t face = pointLightFaceOf(direction);
        const glm::mat4 lightFromWorld = perspectiveLightFromWorld(glm::vec3(0.0f), pointLightFaceDirections()[face]);
        const glm::vec4 clip = clipFromLight * lightFromWorld * glm::vec4(2.0f * direction, 1.0f);
        ASSERT_GT(clip.w, 0.0f);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0f + 1e-5f) << "direction " << i;
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0f + 1e-5f) << "direction " << i;
    }
}
