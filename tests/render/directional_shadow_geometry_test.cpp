// Directional shadows land where geometry says: a box's shadow on the ground against its analytic
// projection and the ray-traced reference, no acne on a plane lit at 60 degrees, light strength.
#include "directional_shadow_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr float kGroundHalf = 8.0f;
constexpr uint32_t kSize = 160;
const Box kBox{{-1.0f, 0.0f, -1.0f}, {1.0f, 3.0f, 1.0f}};
const glm::vec3 kSun = glm::normalize(glm::vec3(1.0f, -1.5f, 0.6f));

Scene boxOnGround(float shadowStrength = 1.0f) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 2.0f * kGroundHalf, material);
    addBox(builder, kBox, material);
    Light sun = makeDirectionalLight(kSun, 3.0f);
    sun.shadowStrength = shadowStrength;
    builder.addLight(sun);
    builder.setCamera(makeLookAtCamera({-1.0f, 9.0f, 8.0f}, {2.0f, 0.0f, 1.0f}, glm::radians(45.0f)));
    return builder.build();
}

// Only a ground plane: every shadow on it would be self-shadowing (acne). The sun makes 60 degrees with
// the plane's normal, so its depth slope across a shadow texel is tan(60) = 1.7 texels.
Scene planeAtSixtyDegrees(float normalBias = 1.0f, float slopeBias = 0.0f) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 60.0f, material);
    const float angle = glm::radians(60.0f), azimuth = glm::radians(15.0f);  // azimuth: off the texel axes
    Light sun = makeDirectionalLight(
        {std::sin(angle) * std::cos(azimuth), -std::cos(angle), std::sin(angle) * std::sin(azimuth)}, 3.0f);
    sun.shadowNormalBias = normalBias;
    sun.shadowBias = slopeBias;
    builder.addLight(sun);
    builder.setCamera(makeLookAtCamera({0.0f, 4.0f, 10.0f}, {0.0f, 0.0f, -6.0f}, glm::radians(60.0f)));
    return builder.build();
}

// Pixels darker than lit (beyond the shadow distance nothing is shadowed anyway).
std::ptrdiff_t countShadowed(const Image& aov) {
    return std::count_if(aov.pixels.begin(), aov.pixels.end(), [](uint8_t v) { return v < 250; });
}

}  // namespace

TEST_F(DirectionalShadowTest, BoxShadowMatchesItsAnalyticProjectionOnTheGround) {
    const Scene scene = boxOnGround();
    const Image aov = renderShadowAov(scene, shadowSettings(), kSize);
    const AnalyticShadow expected =
        analyticGroundShadow(resolveCameraView(scene, kSize, kSize), kGroundHalf, {kBox}, kSun);
    const CompareMetrics metrics = compareShadowImages(aov, expected.shadow, expected.validMask);
    ASSERT_GT(metrics.validPixels, kSize * kSize / 2);
    ASSERT_GT(std::count(expected.shadow.pixels.begin(), expected.shadow.pixels.end(), 0), 1000);
    // Measured: 0 interior errors, 0.3 % of all pixels on the one-pixel edge band.
    EXPECT_EQ(metrics.interiorFalseShadow + metrics.interiorFalseLit, 0u) << toText(metrics);
    EXPECT_LT(metrics.misclassifiedPercent, 1.0) << toText(metrics);
}

TEST_F(DirectionalShadowTest, BoxShadowMatchesTheRayTracedReference) {
    const Scene scene = boxOnGround();
    const Settings settings = shadowSettings();
    const Image aov = renderShadowAov(scene, settings, kSize);
    const CompareMetrics metrics = compareWithReference(scene, aov, settings);
    ASSERT_GT(metrics.validPixels, kSize * kSize / 2);
    EXPECT_EQ(metrics.interiorFalseShadow + metrics.interiorFalseLit, 0u) << toText(metrics);
    EXPECT_LT(metrics.misclassifiedPercent, 1.0) << toText(metrics);
}

TEST_F(DirectionalShadowTest, PlaneAtSixtyDegreesToTheSunShowsNoAcneWithDefaultBiases) {
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        const Image aov = renderShadowAov(planeAtSixtyDegrees(), shadowSettings(30.0f, 4, 1024, filter), 128);
        EXPECT_EQ(countShadowed(aov), 0) << "filter " << shadowFilterName(filter);
    }
}

// The constant normal-offset bias mode (shadows.bias = normal), for the measurements of penumbra/shadows/bias.glsl.
Settings normalBiasSettings(ShadowFilter filter = ShadowFilter::PCF2x2) {
    Settings settings = shadowSettings(30.0f, 4, 1024, filter);
    settings.shadows.bias = ShadowBiasMode::Normal;
    return settings;
}

TEST_F(DirectionalShadowTest, PlaneWithoutAnyBiasShowsAcneInTheNormalBiasMode) {
    // The measurements here can fail: with both biases at 0 the plane shadows itself (measured 58 %).
    const Image aov = renderShadowAov(planeAtSixtyDegrees(0.0f, 0.0f), normalBiasSettings(), 128);
    EXPECT_GT(countShadowed(aov), std::ptrdiff_t(aov.pixels.size() / 5));
}

TEST_F(DirectionalShadowTest, SlopeScaleDepthBiasAloneRemovesAcne) {
    // The light's shadowBias is a slope-scaled depth bias ("Directional Shadows", Configurable Biases),
    // applied by the lit pass to the receiver's slope per texel; measured: 0.5 halves the acne, 1 removes it
    // with PCF2x2.
    const Image aov = renderShadowAov(planeAtSixtyDegrees(0.0f, 1.5f), normalBiasSettings(), 128);
    EXPECT_EQ(countShadowed(aov), 0);
}

TEST_F(DirectionalShadowTest, ConstantNormalBiasRemovesAcneOnThePlaneForEveryFilter) {
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        const Image aov = renderShadowAov(planeAtSixtyDegrees(), normalBiasSettings(filter), 128);
        EXPECT_EQ(countShadowed(aov), 0) << "filter " << shadowFilterName(filter);
    }
}

// The default receiver-plane bias needs no tuning: planes from 10° to 84° off the sun
// never shadow themselves, with every filter, even with the light's shadowNormalBias at 0 (the plane
// compare alone; with the per-texel compare broken this fails at once).
TEST_F(DirectionalShadowTest, ReceiverPlaneBiasKeepsPlanesAtAnyAngleFreeOfAcneWithoutTuning) {
    for (float degrees : {10.0f, 45.0f, 70.0f, 80.0f, 84.0f}) {
        for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF7x7}) {
            SceneBuilder builder;
            const uint32_t material = builder.addMaterial(matteMaterial());
            addGround(builder, 60.0f, material);
            const float angle = glm::radians(degrees), azimuth = glm::radians(15.0f);
            Light sun = makeDirectionalLight(
                {std::sin(angle) * std::cos(azimuth), -std::cos(angle), std::sin(angle) * std::sin(azimuth)}, 3.0f);
            sun.shadowNormalBias = 0.0f;
            builder.addLight(sun);
            builder.setCamera(makeLookAtCamera({0.0f, 4.0f, 10.0f}, {0.0f, 0.0f, -6.0f}, glm::radians(60.0f)));
            const Image aov = renderShadowAov(builder.build(), shadowSettings(30.0f, 4, 1024, filter), 128);
            EXPECT_EQ(countShadowed(aov), 0) << degrees << "° " << shadowFilterName(filter);
        }
    }
}

TEST_F(DirectionalShadowTest, HalfStrengthLightDarkensTheShadowToHalf) {
    const Scene scene = boxOnGround(0.5f);
    const Image aov = renderShadowAov(scene, shadowSettings(), kSize);
    const AnalyticShadow expected =
        analyticGroundShadow(resolveCameraView(scene, kSize, kSize), kGroundHalf, {kBox}, kSun);
    // Interior of the analytic shadow: all 8 neighbours shadowed too, so filtering can't blur it.
    uint32_t checked = 0;
    for (uint32_t y = 2; y + 2 < kSize; ++y) {
        for (uint32_t x = 2; x + 2 < kSize; ++x) {
            bool interior = true;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx)
                    interior = interior && expected.validMask.at(x + dx, y + dy) && !expected.shadow.at(x + dx, y + dy);
            if (!interior) continue;
            ++checked;
            ASSERT_NEAR(int(aov.at(x, y)), 128, 1) << "pixel " << x << ", " << y;
        }
    }
    EXPECT_GT(checked, 500u);
}

TEST_F(DirectionalShadowTest, CasterFarTowardTheLightAndOutOfViewStillCastsItsShadow) {
    // A box hanging 25 m up along the light ray, far outside the camera's view and the cascades' spheres:
    // the light's near plane moves back to hold it, or it is pancaked onto the near plane (depth clamp).
    const Box floating{{-1.0f, 25.0f, -1.0f}, {1.0f, 27.0f, 1.0f}};
    const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const glm::vec3 shift = -sun * (26.0f / -sun.y);  // from the shadow's centre on the ground to the box
    const Box placed{floating.min + glm::vec3(shift.x, 0.0f, shift.z),
                     floating.max + glm::vec3(shift.x, 0.0f, shift.z)};
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 2.0f * kGroundHalf, material);
    addBox(builder, placed, material);
    builder.addLight(makeDirectionalLight(sun, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 8.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, glm::radians(50.0f)));
    const Scene scene = builder.build();
    const Image aov = renderShadowAov(scene, shadowSettings(), kSize);
    const AnalyticShadow expected = analyticGroundShadow(resolveCameraView(scene, kSize, kSize), kGroundHalf, {placed}, sun);
    const CompareMetrics metrics = compareShadowImages(aov, expected.shadow, expected.validMask);
    ASSERT_GT(std::count(expected.shadow.pixels.begin(), expected.shadow.pixels.end(), 0), 1000);
    EXPECT_EQ(metrics.interiorFalseShadow + metrics.interiorFalseLit, 0u) << toText(metrics);
    EXPECT_LT(metrics.misclassifiedPercent, 1.0) << toText(metrics);
}

// Looking straight down, every visible point lies about 10 m deep: the last tight cascade ends there,
// far short of the shadow distance, and must not fade the ground's shadows as if that were its end.
TEST_F(DirectionalShadowTest, TopDownViewWithTightCascadesKeepsItsShadows) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 60.0f, material);
    addBox(builder, {{-1.0f, 0.0f, -1.0f}, {1.0f, 1.5f, 1.0f}}, material);
    builder.addLight(makeDirectionalLight(kSun, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 10.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, glm::radians(60.0f)));
    const Scene scene = builder.build();
    Settings settings;  // the defaults: tight fit, 100 m shadow distance
    const Image aov = renderShadowAov(scene, settings, kSize);
    const CompareMetrics m = compareWithReference(scene, aov, settings);
    EXPECT_GT(m.edgePixels, 40u) << "the box's shadow must show beside it";
    EXPECT_LT(m.misclassifiedPercent, 0.5) << toText(m);
    EXPECT_EQ(m.interiorFalseLit, 0u) << toText(m);
}
