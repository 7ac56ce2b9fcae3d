// Scene changes between frames (scene/scene_edits.h): applied, and refused with a one-line error
// that leaves the scene as it was.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "penumbra/error.h"
#include "scene/scene_edits.h"

namespace penumbra {
namespace {

Scene oneBox() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), material)), glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight(glm::vec3(0, -1, 0), 1.0f));
    return builder.build();
}

TEST(SceneEdits, MovedInstanceGetsNewBounds) {
    Scene scene = oneBox();
    setInstanceWorldTransform(scene, 0, glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)));
    EXPECT_NEAR(scene.instances[0].wsBounds.center().x, 10.0f, 1e-5f);
    EXPECT_GE(scene.wsBounds.max.x, 10.5f - 1e-5f);
}

TEST(SceneEdits, NonFiniteTransformIsRefusedAndNothingChanges) {
    Scene scene = oneBox();
    glm::mat4 bad(1.0f);
    bad[3][0] = NAN;
    EXPECT_THROW(setInstanceWorldTransform(scene, 0, bad), Error);
    EXPECT_EQ(scene.instances[0].worldFromObject, glm::mat4(1.0f));
}

TEST(SceneEdits, UnknownIndicesAreErrors) {
    Scene scene = oneBox();
    EXPECT_THROW(setInstanceWorldTransform(scene, 1, glm::mat4(1.0f)), Error);
    EXPECT_THROW(replaceLight(scene, 3, Light{}), Error);
    EXPECT_THROW(replaceMaterial(scene, 9, Material{}), Error);
}

TEST(SceneEdits, LightDirectionIsNormalized) {
    Scene scene = oneBox();
    Light light = scene.lights[0];
    light.wsDirection = glm::vec3(0, -3, 4);
    replaceLight(scene, 0, light);
    EXPECT_NEAR(glm::length(scene.lights[0].wsDirection), 1.0f, 1e-6f);
}

TEST(SceneEdits, ZeroDirectionOrOutOfRangeShadowValuesAreRefused) {
    Scene scene = oneBox();
    Light light = scene.lights[0];
    light.wsDirection = glm::vec3(0.0f);
    EXPECT_THROW(replaceLight(scene, 0, light), Error);
    light = scene.lights[0];
    light.shadowStrength = 1.5f;
    EXPECT_THROW(replaceLight(scene, 0, light), Error);
    light = scene.lights[0];
    light.shadowNormalBias = -1.0f;
    EXPECT_THROW(replaceLight(scene, 0, light), Error);
    EXPECT_EQ(scene.lights[0].shadowStrength, 1.0f);
}

TEST(SceneEdits, MaterialWithAMissingTextureIsRefused) {
    Scene scene = oneBox();
    Material material = scene.materials[0];
    material.baseColorTexture = 2;
    EXPECT_THROW(replaceMaterial(scene, 0, material), Error);
    material.baseColorTexture = -1;
    material.shadows = MaterialShadowMode::Off;
    replaceMaterial(scene, 0, material);
    EXPECT_EQ(scene.materials[0].shadows, MaterialShadowMode::Off);
}

}  // namespace
}  // namespace penumbra
