// Shadows fade out with view depth and end at the shadow distance (Catlike Coding "Directional Shadows", Max
// Distance, Fading Shadows): the AOV is 255 beyond maxDistance and round(255 (1 - saturate((1 - d/m) / f)))
// in the fade band.
#include "directional_shadow_scenes.h"

#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr float kMaxDistance = 20.0f;
constexpr float kDistanceFade = 0.25f;
constexpr uint32_t kSize = 128;

// A long ground under a roof: the camera stands between them, so every ground point it sees is in the
// roof's shadow. The roof faces up, so the camera below sees only its culled back.
Scene groundUnderRoof() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 200.0f, material);
    const uint32_t roof = builder.addMesh(makePlaneMesh({200.0f, 200.0f}, material));
    builder.addInstance(roof, glm::translate(glm::mat4(1.0f), {0.0f, 3.0f, 0.0f}));
    builder.addLight(makeDirectionalLight({0.2f, -1.0f, 0.1f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 1.5f, 0.0f}, {0.0f, 0.0f, -12.0f}, glm::radians(50.0f)));
    return builder.build();
}

Settings fadeSettings() {
    Settings settings = shadowSettings(kMaxDistance);
    settings.shadows.distanceFade = kDistanceFade;
    return settings;
}

struct GroundPixel {
    uint32_t x, y;
    glm::vec3 wsPosition;
    float viewDepth;
};

std::vector<GroundPixel> groundPixels(const CameraView& view) {
    std::vector<GroundPixel> pixels;
    for (uint32_t y = 0; y < view.height; ++y) {
        for (uint32_t x = 0; x < view.width; ++x) {
            const auto ground = visibleGroundPoint(view, x, y, 100.0f, {});
            if (!ground) continue;
            const float viewDepth = -(view.viewFromWorld * glm::vec4(*ground, 1.0f)).z;
            pixels.push_back({x, y, *ground, viewDepth});
        }
    }
    return pixels;
}

}  // namespace

TEST_F(DirectionalShadowTest, NoShadowBeyondTheMaximumShadowDistance) {
    const Scene scene = groundUnderRoof();
    const Image aov = renderShadowAov(scene, fadeSettings(), kSize);
    uint32_t beyond = 0, nearby = 0;
    for (const GroundPixel& p : groundPixels(resolveCameraView(scene, kSize, kSize))) {
        if (p.viewDepth > kMaxDistance * 1.01f) {
            ++beyond;
            ASSERT_EQ(aov.at(p.x, p.y), 255) << "view depth " << p.viewDepth;
        } else if (p.viewDepth < kMaxDistance * (1.0f - kDistanceFade) * 0.9f) {
            ++nearby;
            ASSERT_EQ(aov.at(p.x, p.y), 0) << "view depth " << p.viewDepth;  // fully shadowed before the band
        }
    }
    EXPECT_GT(beyond, 500u);
    EXPECT_GT(nearby, 500u);
}

TEST_F(DirectionalShadowTest, ShadowStrengthFollowsTheDistanceFadeInTheFadeBand) {
    const Scene scene = groundUnderRoof();
    const Settings settings = fadeSettings();
    const Image aov = renderShadowAov(scene, settings, kSize);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t inBand = 0, partial = 0;
    for (const GroundPixel& p : groundPixels(view)) {
        const float fade = std::clamp((1.0f - p.viewDepth / kMaxDistance) / kDistanceFade, 0.0f, 1.0f);
        if (fade <= 0.0f || fade >= 1.0f) continue;
        // The last cascade's own fade ("Fading Cascades") may also apply near its sphere's rim: keep to
        // the pixels it leaves alone, so this checks the distance fade alone.
        const CascadeSelection selection = selectCascade(plan.directional.gpu, p.wsPosition, p.viewDepth);
        if (std::abs(selection.strength - fade) > 1e-4f) continue;
        ++inBand;
        if (fade > 0.1f && fade < 0.9f) ++partial;
        EXPECT_NEAR(float(aov.at(p.x, p.y)), 255.0f * (1.0f - fade), 1.5f) << "view depth " << p.viewDepth;
    }
    EXPECT_GT(inBand, 300u);
    EXPECT_GT(partial, 200u);
}

TEST_F(DirectionalShadowTest, LastCascadeFadesOutTowardItsSphereRim) {
    // Fading Cascades: in the last cascade the strength also falls with the squared distance from the culling
    // sphere's centre; a wide cascadeFade makes that band cover much of the view.
    const Scene scene = groundUnderRoof();
    Settings settings = fadeSettings();
    settings.shadows.directional.cascadeCount = 2;
    settings.shadows.directional.cascadeFade = 0.5f;
    const Image aov = renderShadowAov(scene, settings, kSize);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t cascadeFaded = 0;
    for (const GroundPixel& p : groundPixels(view)) {
        const CascadeSelection selection = selectCascade(plan.directional.gpu, p.wsPosition, p.viewDepth);
        const float distanceFade = std::clamp((1.0f - p.viewDepth / kMaxDistance) / kDistanceFade, 0.0f, 1.0f);
        if (distanceFade < 1.0f || selection.strength <= 0.05f || selection.strength >= 0.95f) continue;
        ++cascadeFaded;
        EXPECT_NEAR(float(aov.at(p.x, p.y)), 255.0f * (1.0f - selection.strength), 1.5f) << "view depth " << p.viewDepth;
    }
    EXPECT_GT(cascadeFaded, 300u);
}

// URP's fade (GetMainLightShadowFade; shadows.fadeMode = squared): linear in the squared distance
// to the camera, 1 - saturate(d^2 scale + bias) over the band from maxDistance (1 - distanceFade) to
// maxDistance. Off the view axis the camera distance exceeds the view depth, so it fades earlier there
// than the view-depth fade.
TEST_F(DirectionalShadowTest, SquaredFadeFollowsTheSquaredCameraDistance) {
    const Scene scene = groundUnderRoof();
    Settings settings = fadeSettings();
    settings.shadows.fadeMode = ShadowFadeMode::Squared;
    const Image aov = renderShadowAov(scene, settings, kSize);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t partial = 0, differsFromLinear = 0;
    for (const GroundPixel& p : groundPixels(view)) {
        const float d2 = glm::dot(p.wsPosition - view.wsPosition, p.wsPosition - view.wsPosition);
        const float fade = distanceFadeStrength(ShadowFadeMode::Squared, kMaxDistance, kDistanceFade, p.viewDepth, d2);
        const float linear = distanceFadeStrength(ShadowFadeMode::Linear, kMaxDistance, kDistanceFade, p.viewDepth, d2);
        const CascadeSelection selection = selectCascade(plan.directional.gpu, p.wsPosition, p.viewDepth, view.wsPosition);
        if (std::abs(selection.strength - fade) > 1e-4f || fade <= 0.05f || fade >= 0.95f) continue;  // cascade fade too
        ++partial;
        differsFromLinear += std::abs(fade - linear) > 0.1f ? 1 : 0;
        EXPECT_NEAR(float(aov.at(p.x, p.y)), 255.0f * (1.0f - fade), 1.5f) << "camera distance " << std::sqrt(d2);
    }
    EXPECT_GT(partial, 200u);
    EXPECT_GT(differsFromLinear, 50u) << "the test should tell the two fades apart";
}

// The reference traces the same squared fade: the AOV agrees with it in the band.
TEST_F(DirectionalShadowTest, SquaredFadeMatchesTheReference) {
    const Scene scene = groundUnderRoof();
    Settings settings = fadeSettings();
    settings.shadows.fadeMode = ShadowFadeMode::Squared;
    const CompareMetrics m = compareWithReference(scene, renderShadowAov(scene, settings, kSize), settings);
    EXPECT_GT(m.validPixels, 2000u);
    EXPECT_LT(m.meanAbsoluteError, 0.01) << toText(m);
}

// URP's per-light soft flag (_MainLightShadowParams.y) for directional lights too: a "hard" light takes
// one bilinear 2x2 PCF tap whatever directional.filter says.
TEST_F(DirectionalShadowTest, HardDirectionalLightUsesOneTapWhateverTheFilter) {
    Scene scene = boxesInDepthScene();
    Settings settings = shadowSettings(40.0f, 4, 1024, ShadowFilter::PCF7x7);
    const Image soft7x7 = renderShadowAov(scene, settings, kSize);
    scene.lights[0].shadows = LightShadows::Hard;
    const Image hard7x7 = renderShadowAov(scene, settings, kSize);
    settings.shadows.directional.filter = ShadowFilter::PCF2x2;
    const Image hard2x2 = renderShadowAov(scene, settings, kSize);
    // The penumbra (pixels strictly between 12 and 243) is the 2x2 tap's, not the 7x7 tent's. (The images
    // differ in a few pixels: the culling spheres shrink by directional.filter's footprint either way.)
    const double hard = countBetween(hard7x7, 12, 243), tap = countBetween(hard2x2, 12, 243);
    EXPECT_NEAR(hard, tap, 0.05 * tap);
    EXPECT_GT(double(countBetween(soft7x7, 12, 243)), 2.0 * hard);
}
