// Which spot and point lights get shadow tiles: rules, priorities, tile budget.
#include <gtest/gtest.h>

#include <algorithm>

#include "penumbra/camera.h"
#include "shadows/caster_culling.h"
#include "shadows/spot_reservation.h"
#include "spot_test_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

OtherLightReservation reserve(const Scene& scene) {
    return reserveOtherShadows(scene, resolveCameraView(scene, 128, 128), shadowCasterInstances(scene));
}

}  // namespace

TEST(SpotReservation, ShadowedSpotWithACasterInItsConeIsReserved) {
    const OtherLightReservation result = reserve(spotGridScene(1));
    ASSERT_EQ(result.lights.size(), 1u);
    EXPECT_EQ(result.lights[0].sceneLightIndex, 0u);
    EXPECT_EQ(result.lights[0].firstTile, 0u);
    EXPECT_EQ(result.tilesUsed, 1u);
    EXPECT_TRUE(result.droppedLights.empty());
}

TEST(SpotReservation, LightsWithoutShadowsOrStrengthAreSkipped) {
    Scene scene = spotGridScene(3);
    scene.lights[0].shadows = LightShadows::None;
    scene.lights[1].shadowStrength = 0.0f;
    const OtherLightReservation result = reserve(scene);
    ASSERT_EQ(result.lights.size(), 1u);
    EXPECT_EQ(result.lights[0].sceneLightIndex, 2u);
    EXPECT_EQ(result.considered, 3u);
}

TEST(SpotReservation, SpotWhoseConeAndRangeHoldNoCasterIsSkipped) {
    Scene scene = spotGridScene(1);
    scene.lights[0].wsDirection = glm::vec3(0.0f, 1.0f, 0.0f);  // pointing at the sky
    EXPECT_TRUE(reserve(scene).lights.empty());
    scene = spotGridScene(1);
    scene.lights[0].range = 2.0f;  // the box top is 2.6 m below the light, the ground 4 m
    EXPECT_TRUE(reserve(scene).lights.empty());
}

TEST(SpotReservation, SeventeenthSpotIsDroppedWithAWarning) {
    Scene scene = spotGridScene(17);
    const OtherLightReservation result = reserve(scene);
    EXPECT_EQ(result.lights.size(), 16u);
    EXPECT_EQ(result.tilesUsed, 16u);
    ASSERT_EQ(result.droppedLights.size(), 1u);
    ASSERT_EQ(result.warnings.size(), 1u);
    EXPECT_NE(result.warnings[0].find("light " + std::to_string(result.droppedLights[0])), std::string::npos);
    for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(result.lights[i].firstTile, i);
}

TEST(SpotReservation, DroppedLightIsTheOneWithTheLeastScreenInfluence) {
    Scene scene = spotGridScene(17);
    // Light 5 gets a short range: its influence sphere is the smallest, so it is the one left out.
    scene.lights[5].range = 3.5f;
    const OtherLightReservation result = reserve(scene);
    ASSERT_EQ(result.droppedLights.size(), 1u);
    EXPECT_EQ(result.droppedLights[0], 5u);
    const bool reserved = std::any_of(result.lights.begin(), result.lights.end(),
                                      [](const ReservedOtherLight& light) { return light.sceneLightIndex == 5u; });
    EXPECT_FALSE(reserved);
}

TEST(SpotReservation, PointLightCostsSixTilesOfTheSixteen) {
    Scene scene = spotGridScene(4);
    for (int i = 0; i < 3; ++i) {
        Light point = makePointLight(glm::vec3(-6.0f + 4.0f * float(i), 3.0f, -6.0f), 50.0f, 10.0f);
        point.name = "point" + std::to_string(i);
        scene.lights.push_back(point);
    }
    const OtherLightReservation result = reserve(scene);
    // 4 spots + 2 points = 16 tiles; the third point does not fit.
    EXPECT_EQ(result.tilesUsed, 16u);
    EXPECT_EQ(result.lights.size(), 6u);
    ASSERT_EQ(result.droppedLights.size(), 1u);
    EXPECT_EQ(scene.lights[result.droppedLights[0]].type, LightType::Point);
    uint32_t tile = 0;
    for (const ReservedOtherLight& light : result.lights) {
        EXPECT_EQ(light.firstTile, tile);
        tile += light.point ? 6u : 1u;
    }
}

TEST(SpotReservation, InfluenceIsZeroBehindTheCameraFullWhenTheCameraIsInsideAndShrinksWithDistance) {
    const Scene scene = spotGridScene(1);
    const CameraView camera = resolveCameraView(scene, 128, 128);  // at y = 24 looking down
    EXPECT_EQ(screenInfluence({0.0f, 60.0f, 0.0f}, 5.0f, camera), 0.0f);
    EXPECT_EQ(screenInfluence({0.0f, 23.0f, 0.0f}, 5.0f, camera), 1.0f);
    const float near = screenInfluence({0.0f, 12.0f, 0.0f}, 2.0f, camera);
    const float far = screenInfluence({0.0f, 0.0f, 0.0f}, 2.0f, camera);
    EXPECT_GT(near, far);
    EXPECT_GT(far, 0.0f);
    EXPECT_LE(near, 1.0f);
}

TEST(SpotReservation, InfiniteRangeUsesTheSceneBoundsAsFarPlane) {
    Light light = makeSpotLight({0.0f, 4.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 1.0f, 0.0f, 0.5f, 0.4f);
    Aabb bounds{{-20.0f, 0.0f, -20.0f}, {20.0f, 1.0f, 20.0f}};
    EXPECT_NEAR(otherShadowFarDistance(light, bounds), std::sqrt(20.0f * 20.0f * 2.0f + 16.0f), 1e-4f);
    light.range = 7.0f;
    EXPECT_FLOAT_EQ(otherShadowFarDistance(light, bounds), 7.0f);
}

// Reserving again into the same result: a light's answer stands while neither it nor the casters
// changed (the caller's caster epoch), and after a change the caster it found last is tested first.
namespace {

struct Reserving {
    Scene scene;
    CameraView view;
    std::vector<uint32_t> casters;
    OtherLightReservation result;
    explicit Reserving(Scene s) : scene(std::move(s)), view(resolveCameraView(scene, 128, 128)) {
        casters = shadowCasterInstances(scene);
    }
    void reserve(uint64_t casterEpoch) { reserveOtherShadows(scene, view, casters, result, casterEpoch); }
};

// One spot light whose only caster is its box (instance 1): the ground casts no shadow.
Scene oneBoxSpotScene() {
    Scene scene = spotGridScene(1);
    scene.instances[0].castShadows = false;
    return scene;
}

void moveAside(Scene& scene, uint32_t instance) {
    scene.instances[instance].wsBounds.min.x += 20.0f;
    scene.instances[instance].wsBounds.max.x += 20.0f;
}

}  // namespace

TEST(SpotReservation, TheSameLightsAndCasterEpochWalkNoCasterList) {
    Reserving r(spotGridScene(4));
    r.reserve(7);
    EXPECT_EQ(r.result.casterWalks, 4u);
    ASSERT_EQ(r.result.lights.size(), 4u);
    r.reserve(7);
    EXPECT_EQ(r.result.casterWalks, 0u);
    EXPECT_EQ(r.result.lights.size(), 4u);
}

TEST(SpotReservation, AfterACasterChangeEachLightTestsTheCasterItFoundLastFirst) {
    Reserving r(spotGridScene(4));
    r.reserve(7);
    r.reserve(8);
    EXPECT_EQ(r.result.casterWalks, 0u) << "every light's witness is still in its cone";
    EXPECT_EQ(r.result.lights.size(), 4u);
}

TEST(SpotReservation, ALightWhoseOnlyCasterLeftItsConeIsDroppedInTheNextEpoch) {
    Reserving r(oneBoxSpotScene());
    r.reserve(7);
    ASSERT_EQ(r.result.lights.size(), 1u);
    moveAside(r.scene, 1);
    r.reserve(7);
    EXPECT_EQ(r.result.lights.size(), 1u) << "the same epoch: the caller said nothing changed";
    r.reserve(8);
    EXPECT_EQ(r.result.casterWalks, 1u);
    EXPECT_TRUE(r.result.lights.empty());
}

TEST(SpotReservation, ATurnedLightIsLookedAtAgainInTheSameEpoch) {
    Reserving r(oneBoxSpotScene());
    r.reserve(7);
    ASSERT_EQ(r.result.lights.size(), 1u);
    r.scene.lights[0].wsDirection = glm::vec3(0.0f, 1.0f, 0.0f);  // at the sky
    r.reserve(7);
    EXPECT_TRUE(r.result.lights.empty());
}

TEST(SpotReservation, WithoutACasterEpochEveryAnswerIsFoundAgain) {
    Reserving r(oneBoxSpotScene());
    r.reserve(0);
    ASSERT_EQ(r.result.lights.size(), 1u);
    moveAside(r.scene, 1);
    r.reserve(0);
    EXPECT_TRUE(r.result.lights.empty());
}
