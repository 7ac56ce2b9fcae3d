// applySceneDefaults: shadows.maxDistance from the scene's extent when the user set none (a
// model in millimetres, a scene 10^6 m across, a scene in kilometres).
#include <gtest/gtest.h>

#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"
#include "penumbra/settings.h"

using namespace penumbra;

namespace {

// A cube of side `size` at the origin, seen from `distance` away along +Z.
struct CubeView {
    Scene scene;
    CameraView view;
    CubeView(float size, float distance, float zFar = INFINITY) {
        SceneBuilder builder;
        builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f * size), 0)), glm::mat4(1.0f));
        builder.setCamera(makeLookAtCamera({0, 0, distance}, {0, 0, 0}, 0.8f, 0.01f * distance, zFar));
        scene = builder.build();
        view = resolveCameraView(scene, 64, 64);
    }
};

}  // namespace

TEST(SceneDefaults, SceneWithinTheDefaultDistanceKeepsIt) {
    const CubeView cube(4.0f, 20.0f);
    Settings settings;
    EXPECT_TRUE(applySceneDefaults(settings, cube.scene, cube.view).empty());
    EXPECT_EQ(settings.shadows.maxDistance, 100.0f);
}

TEST(SceneDefaults, SceneWithContentNearTheCameraKeepsTheDefaultHoweverLarge) {
    const CubeView ground(1e5f, 10.0f);  // the camera inside a 100 km box: something is within 100 m
    Settings settings;
    EXPECT_TRUE(applySceneDefaults(settings, ground.scene, ground.view).empty());
    EXPECT_EQ(settings.shadows.maxDistance, 100.0f);
}

TEST(SceneDefaults, MillimetreModelSeenWholeGetsTheDistanceToItsFarthestCorner) {
    const CubeView engine(600.0f, 1500.0f);  // 600 mm seen from 1.5 m, in millimetres
    Settings settings;
    const std::vector<std::string> warnings = applySceneDefaults(settings, engine.scene, engine.view);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("shadows.maxDistance is not set"), std::string::npos) << warnings[0];
    EXPECT_NEAR(settings.shadows.maxDistance, glm::length(glm::vec3(300, 300, 1800)), 0.5f);
}

TEST(SceneDefaults, MillionMetreSceneSeenWholeGetsTheDistanceToItsFarthestCorner) {
    const CubeView world(1e6f, 2e6f);
    Settings settings;
    EXPECT_EQ(applySceneDefaults(settings, world.scene, world.view).size(), 1u);
    EXPECT_NEAR(settings.shadows.maxDistance, glm::length(glm::vec3(5e5f, 5e5f, 2.5e6f)), 1e3f);
}

TEST(SceneDefaults, TinySceneGetsTheDistanceToItsFarthestCorner) {
    const CubeView kilometres(0.02f, 0.1f);  // a 20 m house in kilometres, seen from 100 m
    Settings settings;
    EXPECT_EQ(applySceneDefaults(settings, kilometres.scene, kilometres.view).size(), 1u);
    EXPECT_NEAR(settings.shadows.maxDistance, glm::length(glm::vec3(0.01f, 0.01f, 0.11f)), 1e-4f);
}

TEST(SceneDefaults, TheCameraFarPlaneCapsTheChosenDistance) {
    const CubeView engine(600.0f, 1500.0f, 1600.0f);
    Settings settings;
    applySceneDefaults(settings, engine.scene, engine.view);
    EXPECT_EQ(settings.shadows.maxDistance, 1600.0f);
}

TEST(SceneDefaults, AMaxDistanceTheUserSetIsKept) {
    const CubeView engine(600.0f, 1500.0f);
    Settings settings = parseSettingsJson(R"({"shadows": {"maxDistance": 100}})", "test.json");
    EXPECT_TRUE(applySceneDefaults(settings, engine.scene, engine.view).empty());
    EXPECT_EQ(settings.shadows.maxDistance, 100.0f);
    Settings overridden;
    applySettingOverride(overridden, "shadows.maxDistance=50");
    EXPECT_TRUE(applySceneDefaults(overridden, engine.scene, engine.view).empty());
    EXPECT_EQ(overridden.shadows.maxDistance, 50.0f);
}
