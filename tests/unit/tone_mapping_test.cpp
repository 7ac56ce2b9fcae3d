// The tone curves and the sky gradient of shaders/tone_mapping.glsl, compiled here as C++ (the file is
// written in the common subset of GLSL and glm): the functions the lit and background passes run.
#include <cmath>

#include <gtest/gtest.h>

#include "tone_mapping.glsl"

using namespace penumbra::gpu_data;
using namespace penumbra::gpu_data::look;

namespace {

glm::vec3 grey(float value) { return glm::vec3(value); }

// Grey inputs from 0 to 1000 on a log-ish ramp, the outputs of `curve` never decrease.
template <typename Curve>
void expectMonotonic(Curve curve) {
    float previous = curve(grey(0.0f)).r;
    for (float x = 1e-4f; x < 1000.0f; x *= 1.01f) {
        const float y = curve(grey(x)).r;
        ASSERT_GE(y, previous) << "at " << x;
        previous = y;
    }
}

}  // namespace

TEST(ToneMapping, ZeroStaysBlack) {
    for (uint mode : {kToneMapNone, kToneMapNeutral, kToneMapAces}) EXPECT_EQ(toneMap(grey(0.0f), mode), grey(0.0f)) << mode;
}

TEST(ToneMapping, NoneLeavesTheValuesAsTheyAre) {
    for (float x : {0.0f, 0.02f, 0.5f, 1.0f, 3.0f}) EXPECT_EQ(toneMap(grey(x), kToneMapNone), grey(x));
    EXPECT_EQ(toneMap(glm::vec3(0.9f, 0.2f, 0.1f), kToneMapNone), glm::vec3(0.9f, 0.2f, 0.1f));
}

TEST(ToneMapping, CurvesAreMonotonic) {
    expectMonotonic([](glm::vec3 x) { return toneMap(x, kToneMapNeutral); });
    expectMonotonic([](glm::vec3 x) { return toneMap(x, kToneMapAces); });
}

TEST(ToneMapping, NeutralOnlyRemovesItsOffsetBelowTheStartOfCompression) {
    // Grey 0.08 .. 0.76 + 0.04 loses exactly the 0.04 offset; below 0.08 the offset is x - 6.25 x^2
    // (continuous at 0.08, where both give 0.04).
    for (float x : {0.08f, 0.1f, 0.3f, 0.5f, 0.79f}) EXPECT_NEAR(toneMapNeutral(grey(x)).r, x - 0.04f, 1e-6f) << x;
    for (float x : {0.001f, 0.02f, 0.05f, 0.0799f}) EXPECT_NEAR(toneMapNeutral(grey(x)).r, 6.25f * x * x, 1e-6f) << x;
    // A colour below the start keeps its channel differences (no hue shift, no desaturation).
    const glm::vec3 mapped = toneMapNeutral(glm::vec3(0.6f, 0.3f, 0.1f));
    EXPECT_NEAR(mapped.r, 0.56f, 1e-6f);
    EXPECT_NEAR(mapped.g, 0.26f, 1e-6f);
    EXPECT_NEAR(mapped.b, 0.06f, 1e-6f);
}

TEST(ToneMapping, NeutralRollsHighlightsOffTowardWhite) {
    // Past the start the peak is compressed: below 1 for every finite input, 1 in the limit.
    EXPECT_LT(toneMapNeutral(grey(0.9f)).r, 0.9f - 0.04f);
    for (float x : {1.0f, 4.0f, 100.0f}) EXPECT_LT(toneMapNeutral(grey(x)).r, 1.0f) << x;
    EXPECT_GT(toneMapNeutral(grey(1.0e5f)).r, 0.999f);
    // Known value: grey 1 peaks at 0.96 after the offset, newPeak = 1 - 0.24^2 / (0.96 + 0.24 - 0.76).
    EXPECT_NEAR(toneMapNeutral(grey(1.0f)).r, 1.0f - 0.0576f / 0.44f, 1e-5f);
    // A saturated highlight is desaturated toward white: its weakest channel rises.
    const glm::vec3 red = toneMapNeutral(glm::vec3(20.0f, 0.5f, 0.5f));
    EXPECT_GT(red.g, 0.5f);
    EXPECT_LE(red.r, 1.0f);
}

TEST(ToneMapping, AcesFitHasItsPublishedValuesAndWhitePoint) {
    auto aces = [](float x) { return toneMapAces(grey(x)).r; };
    EXPECT_NEAR(aces(1.0f), 2.54f / 3.16f, 1e-5f);
    EXPECT_NEAR(aces(0.18f), 0.18f * (2.51f * 0.18f + 0.03f) / (0.18f * (2.43f * 0.18f + 0.59f) + 0.14f), 1e-6f);
    // White point: f(x) = 1 where 0.08 x^2 - 0.56 x - 0.14 = 0, x = (0.56 + sqrt(0.3584)) / 0.16.
    const float white = (0.56f + std::sqrt(0.3584f)) / 0.16f;
    EXPECT_LT(aces(white * 0.99f), 1.0f);
    EXPECT_EQ(aces(white * 1.01f), 1.0f);
    EXPECT_EQ(aces(1000.0f), 1.0f);
}

TEST(ToneMapping, ModesPickTheirCurves) {
    const glm::vec3 x(0.9f, 0.4f, 2.0f);
    EXPECT_EQ(toneMap(x, kToneMapNeutral), toneMapNeutral(x));
    EXPECT_EQ(toneMap(x, kToneMapAces), toneMapAces(x));
    EXPECT_NE(toneMapNeutral(x), toneMapAces(x));
}

TEST(Background, SkyGoesFromGroundThroughHorizonToZenith) {
    EXPECT_EQ(backgroundRadiance(glm::vec3(0, 1, 0)), kSkyZenith);
    EXPECT_EQ(backgroundRadiance(glm::vec3(0, 5, 0)), kSkyZenith);  // any length
    EXPECT_EQ(backgroundRadiance(glm::vec3(1, 0, 0)), kSkyHorizon);
    EXPECT_EQ(backgroundRadiance(glm::vec3(0, -1, 0)), kSkyGround);
    EXPECT_EQ(backgroundRadiance(glm::vec3(0, -1, 1)), kSkyGround);  // 45 degrees down: ground
    // Continuous at the horizon, and brighter there than at the zenith and the ground.
    const glm::vec3 justAbove = backgroundRadiance(glm::vec3(1, 1e-6f, 0));
    const glm::vec3 justBelow = backgroundRadiance(glm::vec3(1, -1e-6f, 0));
    EXPECT_LT(glm::length(justAbove - justBelow), 0.01f);
    EXPECT_GT(kSkyHorizon.g, kSkyZenith.g);
    EXPECT_GT(kSkyHorizon.g, kSkyGround.g);
    EXPECT_GT(kSkyZenith.b, kSkyZenith.r);  // blue sky
}
