// Soft cascade blending (Catlike Coding "Directional Shadows", Blending Cascades) weighs the two cascades by
// the fade of the smaller one: at a blend weight w of cascade i the result is w * cascade i + (1 - w) *
// cascade i + 1, so it never strays from cascade i's value (the hard blend's) by more than (1 - w). A swapped
// lerp fails this where the cascades disagree.
#include <cmath>
#include <utility>

#include "directional_shadow_scenes.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 160;

// A long wall beside the view axis under a sun from the side: its shadow edge on the ground runs away
// from the camera through the blend band of cascade 0. A large normal bias moves that edge by a
// different amount in each cascade (it scales with the cascade's texel), so the cascades disagree on a
// strip along the edge.
Scene wallAlongTheView() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 100.0f, material);
    addBox(builder, {{0.9f, 0.0f, -45.0f}, {1.1f, 1.0f, -1.0f}}, material);
    Light sun = makeDirectionalLight({-1.0f, -1.0f, 0.0f}, 3.0f);
    sun.shadowNormalBias = 6.0f;
    builder.addLight(sun);
    builder.setCamera(makeLookAtCamera({0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, -10.0f}, glm::radians(60.0f)));
    return builder.build();
}

// Whether wsPosition lies in the fade band of sphere `cascade` (its fade below 1), whatever the next sphere.
bool inFadeBandOfSphere(const gpu_data::DirectionalShadowData& data, int cascade, glm::vec3 wsPosition) {
    const gpu_data::DirectionalCascade& sphere = data.cascades[cascade];
    const glm::vec3 offset = wsPosition - glm::vec3(sphere.cullingSphere);
    const float distanceSquared = glm::dot(offset, offset);
    return distanceSquared < sphere.cullingSphere.w &&
           fadedShadowStrength(distanceSquared, sphere.invRadiusSquared, data.cascadeFadeScale) < 1.0f;
}

// Soft blending with wide (30 %) fade bands, 4 cascades over 40 m; the constant normal-offset bias, whose
// offset grows with the cascade's texel (so cascades disagree along shadow edges).
Settings softBlendSettings() {
    Settings settings = shadowSettings(40.0f, 4, 1024, ShadowFilter::PCF2x2, CascadeBlend::Soft);
    settings.shadows.directional.cascadeFade = 0.3f;
    settings.shadows.bias = ShadowBiasMode::Normal;
    return settings;
}

}  // namespace

class CascadeBlendTest : public DirectionalShadowTest {
protected:
    // The shadow AOV with hard blending (cascade i alone in its band) and with `settings`' soft blending.
    std::pair<Image, Image> renderHardAndSoft(const Scene& scene, const Settings& settings) {
        Settings hard = settings;
        hard.shadows.directional.cascadeBlend = CascadeBlend::Hard;
        return {renderShadowAov(scene, hard, kSize), renderShadowAov(scene, settings, kSize)};
    }
};

TEST_F(CascadeBlendTest, SoftBlendStaysWithinOneMinusTheWeightOfTheSmallerCascade) {
    const Scene scene = wallAlongTheView();
    const Settings settings = softBlendSettings();
    const auto [hard, soft] = renderHardAndSoft(scene, settings);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    const gpu_data::DirectionalShadowData& data = plan.directional.gpu;
    uint32_t bandPixels = 0, disagreeing = 0, violations = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const auto ground = visibleGroundPoint(view, x, y, 50.0f, {{{0.9f, 0.0f, -45.0f}, {1.1f, 1.0f, -1.0f}}});
            if (!ground) continue;
            const float viewDepth = -(view.viewFromWorld * glm::vec4(*ground, 1.0f)).z;
            const CascadeSelection selection = selectCascade(data, *ground, viewDepth);
            const float w = selection.cascadeBlend;
            if (selection.cascadeIndex != 0 || w >= 1.0f || w <= 0.0f) continue;  // cascade 0's blend band
            ++bandPixels;
            const int difference = std::abs(int(soft.at(x, y)) - int(hard.at(x, y)));
            disagreeing += difference > 40 ? 1 : 0;
            violations += float(difference) > (1.0f - w) * 255.0f + 3.0f ? 1 : 0;
        }
    EXPECT_GT(bandPixels, 500u);
    EXPECT_GT(disagreeing, 10u) << "the cascades should disagree somewhere in the band, or the test has no teeth";
    EXPECT_EQ(violations, 0u);
}

// Spheres need not nest: through a narrow lens (15°), sphere 0 ends 0.7 m from the camera inside its
// fade band while sphere 1 only begins 3.9 m away. A point in that band must keep cascade 0: tile 1
// never saw it.
TEST_F(CascadeBlendTest, SoftBlendNeverReadsACascadeWhoseSphereMissesThePoint) {
    Scene scene = wallAlongTheView();
    scene.camera = makeLookAtCamera({-0.1f, 0.6f, -5.0f}, {-0.1f, 0.0f, -5.3f}, glm::radians(15.0f));
    const Settings settings = softBlendSettings();
    const auto [hard, soft] = renderHardAndSoft(scene, settings);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const gpu_data::DirectionalShadowData data = ShadowPlanner::plan(scene, view, settings.shadows).directional.gpu;
    uint32_t outsideNext = 0, blended = 0, shadowEdge = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const auto ground = visibleGroundPoint(view, x, y, 50.0f, {});
            if (!ground || !inFadeBandOfSphere(data, 0, *ground)) continue;
            const glm::vec4 next = data.cascades[1].cullingSphere;
            const glm::vec3 offset = *ground - glm::vec3(next);
            if (glm::dot(offset, offset) < next.w) continue;
            ++outsideNext;
            shadowEdge += hard.at(x, y) < 128 ? 1 : 0;
            blended += std::abs(int(soft.at(x, y)) - int(hard.at(x, y))) > 1 ? 1 : 0;
        }
    EXPECT_GT(outsideNext, kSize * kSize / 4);
    EXPECT_GT(shadowEdge, 100u) << "the wall's shadow should be in view";
    EXPECT_EQ(blended, 0u);
}
