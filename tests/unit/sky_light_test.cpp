// The ambient sky light of shaders/sky_light.glsl, compiled here as C++ (the file is written in the
// common subset of GLSL and glm): the function the lit pass runs, against the irradiance of the
// background gradient integrated numerically.
#include <cmath>

#include <gtest/gtest.h>

#include "sky_light.glsl"

using namespace penumbra::gpu_data::look;

namespace {

constexpr float kPi = 3.14159265358979f;

// E(n) / pi = (1 / pi) integral of backgroundRadiance(w) max(n.w, 0) over the sphere: midpoint rule
// on a 600 x 1200 grid of polar angle (from +Y, so the horizon lies on a cell border) and azimuth.
glm::vec3 integratedSkyIrradiance(glm::vec3 n) {
    constexpr int kRows = 600;
    const double step = double(kPi) / kRows;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < kRows; ++i) {
        const double theta = (i + 0.5) * step;
        const glm::vec3 radiance = backgroundRadiance(glm::vec3(std::sin(theta), std::cos(theta), 0.0));
        for (int j = 0; j < 2 * kRows; ++j) {
            const double phi = (j + 0.5) * step;
            const glm::dvec3 w(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            const double cosine = glm::dot(glm::dvec3(n), w);
            if (cosine > 0.0) sum += glm::dvec3(radiance) * (cosine * std::sin(theta) * step * step);
        }
    }
    return glm::vec3(sum / double(kPi));
}

// The unit normal `degrees` from straight up, tilted toward +X.
glm::vec3 tilted(float degrees) {
    const float radians = degrees * kPi / 180.0f;
    return {std::sin(radians), std::cos(radians), 0.0f};
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << what << ", channel " << c;
}

}  // namespace

TEST(SkyLight, StraightUpIsTheSkysCosineWeightedMeanTimesAmbient) {
    // The upper gradient mix(horizon, zenith, sqrt(mu)) weighted by 2 mu dmu: the zenith's weight is 0.8.
    const glm::vec3 sky = mix(kSkyHorizon, kSkyZenith, 0.8f);
    expectNear(ambientRadiance({0, 1, 0}, glm::vec3(1.0f), 0.5f), 0.5f * sky, 1e-6f, "straight up");
    expectNear(skyIrradiance({0, 1, 0}), integratedSkyIrradiance({0, 1, 0}), 1e-3f, "straight up, integrated");
}

TEST(SkyLight, StraightDownIsTheGroundsCosineWeightedMean) {
    // The lower gradient reaches the ground colour 15 degrees below the horizon: its weight is 0.9875.
    const glm::vec3 ground = mix(kSkyHorizon, kSkyGround, 0.9875f);
    expectNear(ambientRadiance({0, -1, 0}, glm::vec3(1.0f), 1.0f), ground, 1e-6f, "straight down");
    expectNear(skyIrradiance({0, -1, 0}), integratedSkyIrradiance({0, -1, 0}), 1e-3f, "straight down, integrated");
}

TEST(SkyLight, AVerticalSurfaceGetsTheExactIrradianceOfTheHorizonsBand) {
    // Any horizontal normal: the fit's horizon term makes it exact there, where the classic two-colour
    // hemisphere light mix(ground, sky, 0.5) is 12 to 22 % short (the bright horizon).
    const glm::vec3 exact = integratedSkyIrradiance({1, 0, 0});
    expectNear(skyIrradiance({1, 0, 0}), exact, 1e-3f, "vertical");
    expectNear(skyIrradiance({0, 0, -1}), exact, 1e-3f, "vertical, another azimuth");
    const glm::vec3 classic = mix(skyIrradiance({0, -1, 0}), skyIrradiance({0, 1, 0}), 0.5f);
    EXPECT_LT(classic.g, 0.85f * exact.g);
}

TEST(SkyLight, EveryNormalIsWithin3PercentOfTheIntegratedGradient) {
    for (float degrees = 0.0f; degrees <= 180.0f; degrees += 10.0f) {
        const glm::vec3 exact = integratedSkyIrradiance(tilted(degrees));
        const glm::vec3 fit = skyIrradiance(tilted(degrees));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(fit[c], exact[c], 0.03f * exact[c]) << degrees << " degrees from up, channel " << c;
    }
}

TEST(SkyLight, ScalesWithAmbientAndBaseColourAndZeroTurnsItOff) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f));
    const glm::vec3 base(0.8f, 0.4f, 0.1f);
    EXPECT_EQ(ambientRadiance(n, base, 0.0f), glm::vec3(0.0f));
    expectNear(ambientRadiance(n, base, 0.25f), 0.25f * skyIrradiance(n) * base, 1e-7f, "scaled");
    expectNear(ambientRadiance(n, base, 1.0f), 4.0f * ambientRadiance(n, base, 0.25f), 1e-6f, "linear in ambient");
}

TEST(SkyLight, UpFacingSurfacesAreBlueAndBrighterThanDownFacingOnes) {
    const glm::vec3 up = skyIrradiance({0, 1, 0}), down = skyIrradiance({0, -1, 0});
    EXPECT_GT(up.b, up.r);
    EXPECT_GT(up.g + up.b, down.g + down.b);
    for (float degrees = 0.0f; degrees <= 180.0f; degrees += 5.0f)
        for (int c = 0; c < 3; ++c) EXPECT_GT(skyIrradiance(tilted(degrees))[c], 0.0f) << degrees;
}
