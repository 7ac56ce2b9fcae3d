#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/caster_culling.h"
#include "shadows/light_reservation.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

std::vector<ReservedDirectionalLight> reserve(const Scene& scene, uint32_t cascadeCount = 4) {
    ShadowSettings settings;
    settings.maxDistance = 50.0f;
    settings.directional.cascadeCount = cascadeCount;
    const CameraView camera = cameraLookingAt({0, 5, 20}, {0, 0, 0});
    return reserveDirectionalShadows(scene, computeCascadeSpheres(camera, settings), shadowCasterInstances(scene),
                                     cascadeCount);
}

Scene sceneWithCaster() {
    Scene scene = baseScene();
    addBox(scene, {-1, 0, -1}, {1, 2, 1});
    return scene;
}

}  // namespace

TEST(LightReservation, ReservesALightWithACasterInRange) {
    Scene scene = sceneWithCaster();
    addDirectionalLight(scene, {0.2f, -1, 0.1f});
    EXPECT_EQ(reserve(scene).size(), 1u);
}

TEST(LightReservation, SkipsALightWithShadowsNone) {
    Scene scene = sceneWithCaster();
    addDirectionalLight(scene, {0, -1, 0}, 1.0f, LightShadows::None);
    EXPECT_TRUE(reserve(scene).empty());
}

TEST(LightReservation, SkipsALightWithZeroStrength) {
    Scene scene = sceneWithCaster();
    addDirectionalLight(scene, {0, -1, 0}, 0.0f);
    EXPECT_TRUE(reserve(scene).empty());
}

TEST(LightReservation, SkipsALightWithNoCasterInTheShadowVolume) {
    Scene scene = baseScene();
    addBox(scene, {500, 0, 500}, {501, 1, 501});                 // far outside the shadow distance
    addBox(scene, {-1, 0, -1}, {1, 2, 1}, /*castShadows=*/false);  // in range but casts no shadow
    addBox(scene, {-1, 0, -1}, {1, 2, 1}, true, /*shadows Off mesh=*/1);
    addDirectionalLight(scene, {0, -1, 0});
    EXPECT_TRUE(reserve(scene).empty());
}

TEST(LightReservation, ReservesForAnOffScreenCasterBetweenTheLightAndTheShadowRegion) {
    Scene scene = baseScene();
    addBox(scene, {-1, 300, -1}, {1, 301, 1});  // straight above the view, far beyond maxDistance
    addDirectionalLight(scene, {0, -1, 0});
    EXPECT_EQ(reserve(scene).size(), 1u);
}

TEST(LightReservation, DropsTheFifthShadowedLight) {
    Scene scene = sceneWithCaster();
    for (int i = 0; i < 5; ++i) addDirectionalLight(scene, {0.1f * float(i), -1, 0});
    const std::vector<ReservedDirectionalLight> reserved = reserve(scene, 2);
    ASSERT_EQ(reserved.size(), 4u);
    for (uint32_t slot = 0; slot < 4; ++slot) {
        EXPECT_EQ(reserved[slot].sceneLightIndex, slot);
        EXPECT_EQ(reserved[slot].firstTile, slot * 2);
    }
}

TEST(LightReservation, IgnoresSpotAndPointLightsAndKeepsSceneIndices) {
    Scene scene = sceneWithCaster();
    addDirectionalLight(scene, {0, -1, 0});
    scene.lights.back().type = LightType::Spot;
    addDirectionalLight(scene, {0, -1, 0}, 0.5f);
    const std::vector<ReservedDirectionalLight> reserved = reserve(scene);
    ASSERT_EQ(reserved.size(), 1u);
    EXPECT_EQ(reserved[0].sceneLightIndex, 1u);
    EXPECT_EQ(reserved[0].firstTile, 0u);
}

TEST(LightReservation, CopiesStrengthAndBiasesFromTheLight) {
    Scene scene = sceneWithCaster();
    addDirectionalLight(scene, {0, -2, 0}, 0.75f);
    scene.lights[0].shadowBias = 0.6f;
    scene.lights[0].shadowNormalBias = 0.4f;
    scene.lights[0].shadowNearPlane = 2.0f;
    const std::vector<ReservedDirectionalLight> reserved = reserve(scene);
    ASSERT_EQ(reserved.size(), 1u);
    EXPECT_EQ(reserved[0].strength, 0.75f);
    EXPECT_EQ(reserved[0].slopeScaleBias, 0.6f);
    EXPECT_EQ(reserved[0].normalBias, 0.4f);
    EXPECT_EQ(reserved[0].nearPlaneOffset, 2.0f);
    EXPECT_NEAR(reserved[0].wsDirection.y, -1.0f, 1e-6f);
}
