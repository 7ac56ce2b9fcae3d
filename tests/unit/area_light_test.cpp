// The reference's area lights (reference/area_light.h): sample points cover the unit disk evenly, and
// shadow rays go to the sun's cone or to a spot's emitter disk.
#include <cmath>

#include <gtest/gtest.h>

#include "reference/area_light.h"
#include "penumbra/scene_builder.h"

using namespace penumbra;

TEST(AreaLight, VogelSamplesFillTheUnitDiskEvenly) {
    constexpr uint32_t n = 256;
    glm::vec2 mean(0.0f);
    uint32_t inner = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec2 p = vogelDiskSample(i, n, 0.3f);
        EXPECT_LE(glm::length(p), 1.0f + 1e-6f);
        mean += p / float(n);
        inner += glm::length(p) < std::sqrt(0.5f) ? 1 : 0;  // half the disk's area
    }
    EXPECT_LT(glm::length(mean), 0.02f);
    EXPECT_NEAR(float(inner) / float(n), 0.5f, 0.02f);
}

TEST(AreaLight, SunRaysStayWithinItsAngularRadius) {
    Light sun = makeDirectionalLight({0.0f, -1.0f, 0.2f}, 3.0f);
    sun.shadowLightSize = 4.0f;  // degrees across
    const glm::vec3 toSun = -glm::normalize(sun.wsDirection);
    float widest = 0.0f;
    for (glm::vec2 disk : {glm::vec2(1, 0), glm::vec2(0, -1), glm::vec2(0.6f, 0.8f), glm::vec2(0.0f)}) {
        const AreaLightRay ray = areaLightRay(sun, glm::vec3(1, 2, 3), disk, 1e-4f);
        widest = std::max(widest, std::acos(std::min(1.0f, glm::dot(ray.wsDirection, toSun))));
        EXPECT_TRUE(std::isinf(ray.tFar));
    }
    EXPECT_NEAR(glm::degrees(widest), 2.0f, 1e-3f);
}

TEST(AreaLight, SpotRaysEndOnItsEmitterDiskFacingThePoint) {
    Light spot = makeSpotLight({0, 4, 0}, {0, -1, 0}, 50.0f, 10.0f, 0.6f, 0.5f);
    spot.shadowLightSize = 0.2f;
    const glm::vec3 origin(0.0f, 0.0f, 0.0f);
    const AreaLightRay ray = areaLightRay(spot, origin, {1.0f, 0.0f}, 0.0f);
    const glm::vec3 target = origin + ray.wsDirection * ray.tFar;
    EXPECT_NEAR(glm::length(target - spot.wsPosition), 0.2f, 1e-4f);
    EXPECT_NEAR(glm::dot(target - spot.wsPosition, glm::vec3(0, 1, 0)), 0.0f, 1e-4f);  // the disk faces the point
}
