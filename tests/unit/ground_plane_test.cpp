// addGroundPlane (penumbra/scene_loading.h): the plane --ground puts under a lone model.
#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "error_message.h"
#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "scene/scene_validation.h"

using namespace penumbra;

namespace {

// A 2 x 2 x 4 box floating with its bottom at y = 1, centred on (3, 2, -1), without a camera.
Scene loneBox() {
    SceneBuilder builder;
    builder.addInstance(builder.addMesh(makeBoxMesh({1, 1, 2}, 0)), glm::translate(glm::mat4(1.0f), glm::vec3(3, 2, -1)));
    return builder.build();
}

}  // namespace

TEST(GroundPlane, IsAnUpwardSquareOfFourTimesTheWidthJustBelowTheScene) {
    Scene scene = loneBox();
    const Aabb before = scene.wsBounds;
    addGroundPlane(scene);
    ASSERT_EQ(scene.instances.size(), 2u);
    const Instance& ground = scene.instances.back();
    const Mesh& mesh = scene.meshes.at(ground.meshIndex);
    // 4 x the larger horizontal extent (4 m along z), centred under the box, 1e-4 of 4 m below it.
    EXPECT_FLOAT_EQ(ground.wsBounds.min.x, 3.0f - 8.0f);
    EXPECT_FLOAT_EQ(ground.wsBounds.max.x, 3.0f + 8.0f);
    EXPECT_FLOAT_EQ(ground.wsBounds.min.z, -1.0f - 8.0f);
    EXPECT_FLOAT_EQ(ground.wsBounds.max.z, -1.0f + 8.0f);
    EXPECT_FLOAT_EQ(ground.wsBounds.min.y, 1.0f - 4e-4f);
    EXPECT_FLOAT_EQ(ground.wsBounds.max.y, 1.0f - 4e-4f);
    for (const Vertex& v : mesh.vertices) EXPECT_EQ(v.osNormal, glm::vec3(0, 1, 0));
    ASSERT_EQ(mesh.indices.size(), 6u);
    // Front faces (counter-clockwise) face up: the first triangle's winding normal is +Y.
    const glm::vec3 a = mesh.vertices[mesh.indices[0]].osPosition, b = mesh.vertices[mesh.indices[1]].osPosition,
                    c = mesh.vertices[mesh.indices[2]].osPosition;
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);
    // The scene's bounds hold both; the box's instance is untouched.
    EXPECT_EQ(scene.wsBounds.min, glm::vec3(-5.0f, 1.0f - 4e-4f, -9.0f));
    EXPECT_EQ(scene.wsBounds.max, glm::vec3(11.0f, before.max.y, 7.0f));
    EXPECT_EQ(scene.instances.front().wsBounds.min, before.min);
    EXPECT_NO_THROW(validateScene(scene));
}

TEST(GroundPlane, IsMatteNeutralGreyReceivingShadowsAndCastingNone) {
    Scene scene = loneBox();
    addGroundPlane(scene);
    const Instance& ground = scene.instances.back();
    const Material& material = scene.materials.at(scene.meshes.at(ground.meshIndex).materialIndex);
    EXPECT_EQ(material.baseColorFactor, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    EXPECT_EQ(material.metallic, 0.0f);
    EXPECT_EQ(material.roughness, 1.0f);
    EXPECT_EQ(material.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(material.baseColorTexture, -1);
    EXPECT_FALSE(material.unlit);
    EXPECT_FALSE(material.doubleSided);
    EXPECT_TRUE(material.receiveShadows);
    EXPECT_FALSE(ground.castShadows);
    EXPECT_EQ(scene.materials.size(), 2u) << "the box's material stays";
}

TEST(GroundPlane, SceneWithoutCameraKeepsTheFramingOfTheModel) {
    Scene scene = loneBox();
    const Camera framing = autoFramingCamera(scene.wsBounds);
    addGroundPlane(scene);
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->worldFromView, framing.worldFromView);
    EXPECT_EQ(scene.camera->yfov, framing.yfov);
    EXPECT_TRUE(scene.cameras.empty());
}

TEST(GroundPlane, SceneCameraStays) {
    Scene scene = loneBox();
    scene.camera = makeLookAtCamera({0, 5, 20}, {0, 0, 0}, 0.7f);
    const glm::mat4 own = scene.camera->worldFromView;
    addGroundPlane(scene);
    EXPECT_EQ(scene.camera->worldFromView, own);
}

TEST(GroundPlane, FlatSceneFallsBackToItsHeightThenToOne) {
    // A vertical pole (no horizontal extent) 2 m high: a plane of 8 m.
    SceneBuilder builder;
    Mesh pole;
    pole.vertices = {{{0, 0, 0}, {1, 0, 0}, {0, 0}}, {{0, 2, 0}, {1, 0, 0}, {0, 0}}, {{0, 2, 0}, {1, 0, 0}, {0, 0}}};
    pole.indices = {0, 1, 2};
    builder.addInstance(builder.addMesh(pole), glm::mat4(1.0f));
    Scene scene = builder.build();
    addGroundPlane(scene);
    EXPECT_FLOAT_EQ(scene.instances.back().wsBounds.extent().x, 8.0f);
}

TEST(GroundPlane, SceneWithoutGeometryIsAnError) {
    Scene empty;
    EXPECT_NE(penumbra::testing::errorMessage([&] { addGroundPlane(empty); }).find("without geometry"), std::string::npos);
}

TEST(GroundPlane, LoadSceneAddsItWhenAsked) {
    const Scene plain = loadScene("");
    SceneSourceOptions options;
    options.addGround = true;
    const Scene grounded = loadScene("", options);
    ASSERT_EQ(grounded.instances.size(), plain.instances.size() + 1);
    EXPECT_EQ(grounded.instances.back().nodeName, "ground");
    EXPECT_FLOAT_EQ(grounded.instances.back().wsBounds.min.y,
                    plain.wsBounds.min.y - 1e-4f * std::max(plain.wsBounds.extent().x, plain.wsBounds.extent().z));
    EXPECT_EQ(plain.camera->worldFromView, grounded.camera->worldFromView) << "the demo's own camera";
}
