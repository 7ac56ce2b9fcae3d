// Up to four shadowed directional lights share the atlas (Catlike Coding "Directional Shadows", Multiple
// Lights): each light's AOV shows its own shadow; a fifth shadowed light gets no tiles and casts no shadow.
#include "directional_shadow_scenes.h"

#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr float kGroundHalf = 10.0f;
constexpr uint32_t kSize = 128;
const Box kBox{{-1.0f, 0.0f, -1.0f}, {1.0f, 1.5f, 1.0f}};
const glm::vec3 kDirections[5] = {
    {1.0f, -1.2f, 0.2f}, {-1.0f, -1.3f, 0.3f}, {0.2f, -1.1f, 1.0f}, {-0.3f, -1.4f, -1.0f}, {0.7f, -1.0f, -0.7f}};

Scene boxUnderSuns(uint32_t lightCount) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 2.0f * kGroundHalf, material);
    addBox(builder, kBox, material);
    for (uint32_t i = 0; i < lightCount; ++i) builder.addLight(makeDirectionalLight(kDirections[i], 1.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 12.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, glm::radians(50.0f)));
    return builder.build();
}

}  // namespace

TEST_F(DirectionalShadowTest, FourShadowedDirectionalLightsEachCastTheirOwnShadow) {
    const Scene scene = boxUnderSuns(4);
    const Settings settings = shadowSettings(20.0f, 1, 1024);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    for (uint32_t light = 0; light < 4; ++light) {
        const Image aov = renderShadowAov(scene, settings, kSize, light);
        const AnalyticShadow expected = analyticGroundShadow(view, kGroundHalf, {kBox}, kDirections[light]);
        const CompareMetrics metrics = compareShadowImages(aov, expected.shadow, expected.validMask);
        ASSERT_GT(std::count(expected.shadow.pixels.begin(), expected.shadow.pixels.end(), 0), 100) << light;
        // Measured: interior 0 - 0.01 %, all 0.2 - 0.3 % (edge pixels).
        EXPECT_LT(metrics.interiorMisclassifiedPercent, 0.05) << "light " << light << "\n" << toText(metrics);
        EXPECT_LT(metrics.misclassifiedPercent, 1.0) << "light " << light << "\n" << toText(metrics);
    }
}

// Virtual shadow maps: each light's own map in the shared pool (render/virtual_shadows.h).
TEST_F(DirectionalShadowTest, FourDirectionalLightsEachReadTheirOwnVirtualShadowMap) {
    const Scene scene = boxUnderSuns(4);
    Settings settings = shadowSettings(20.0f, 1, 1024);
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.virtualMaps.poolPages = 256;
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    for (uint32_t light = 0; light < 4; ++light) {
        const Image aov = renderShadowAov(scene, settings, kSize, light);
        const AnalyticShadow expected = analyticGroundShadow(view, kGroundHalf, {kBox}, kDirections[light]);
        const CompareMetrics metrics = compareShadowImages(aov, expected.shadow, expected.validMask);
        // Measured: interior 0 %, all 0 - 0.07 % (edge pixels); the cascades above 0.2 - 0.3 %.
        EXPECT_LT(metrics.interiorMisclassifiedPercent, 0.05) << "light " << light << "\n" << toText(metrics);
        EXPECT_LT(metrics.misclassifiedPercent, 0.2) << "light " << light << "\n" << toText(metrics);
    }
}

TEST_F(DirectionalShadowTest, FifthShadowedDirectionalLightGetsNoShadow) {
    const Scene scene = boxUnderSuns(5);
    const Settings settings = shadowSettings(20.0f, 1, 1024);
    const ShadowFrame plan = ShadowPlanner::plan(scene, resolveCameraView(scene, kSize, kSize), settings.shadows);
    ASSERT_EQ(plan.directional.lights.size(), 4u);
    EXPECT_EQ(plan.directional.slotOfSceneLight[4], -1);

    const Image fifth = renderShadowAov(scene, settings, kSize, 4);
    EXPECT_EQ(std::count(fifth.pixels.begin(), fifth.pixels.end(), 255), std::ptrdiff_t(fifth.pixels.size()));
    // The four reserved lights still cast theirs.
    const Image fourth = renderShadowAov(scene, settings, kSize, 3);
    EXPECT_GT(std::count_if(fourth.pixels.begin(), fourth.pixels.end(), [](uint8_t v) { return v < 128; }), 100);
}

TEST_F(DirectionalShadowTest, SunListedAfterASpotLightCastsItsShadowUnderItsOwnIndex) {
    // Scene light indices, shadow slots and the lit pass's light order differ: the AOV follows the index.
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 2.0f * kGroundHalf, material);
    addBox(builder, kBox, material);
    Light spot = makeSpotLight({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 10.0f, 20.0f, 0.5f, 0.4f);
    spot.shadows = LightShadows::None;
    builder.addLight(spot);
    builder.addLight(makeDirectionalLight(kDirections[0], 1.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 12.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, glm::radians(50.0f)));
    const Scene scene = builder.build();
    const Image aov = renderShadowAov(scene, shadowSettings(20.0f, 1, 1024), kSize, 1);
    const AnalyticShadow expected =
        analyticGroundShadow(resolveCameraView(scene, kSize, kSize), kGroundHalf, {kBox}, kDirections[0]);
    const CompareMetrics metrics = compareShadowImages(aov, expected.shadow, expected.validMask);
    EXPECT_LT(metrics.interiorMisclassifiedPercent, 0.05) << toText(metrics);
    EXPECT_LT(metrics.misclassifiedPercent, 1.0) << toText(metrics);
}
