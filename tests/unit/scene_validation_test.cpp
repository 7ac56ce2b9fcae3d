// validateScene: the checks a Scene from any source passes before the renderer puts it on the GPU.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "error_message.h"
#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"
#include "scene/scene_validation.h"

using namespace penumbra;

namespace {

// A box on the default material under a sun, built like a program would build one.
Scene validScene() {
    SceneBuilder builder;
    const uint32_t mesh = builder.addMesh(makeBoxMesh(glm::vec3(0.5f), 0));
    builder.addInstance(mesh, glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight({0, -1, 0}, 3.0f));
    return builder.build();
}

std::string validationError(const Scene& scene) {
    return penumbra::testing::errorMessage([&] { validateScene(scene); });
}

}  // namespace

TEST(SceneValidation, ABuiltSceneIsValid) { EXPECT_EQ(validationError(validScene()), ""); }

TEST(SceneValidation, IndexNotBelowTheVertexCountIsAnError) {
    Scene scene = validScene();
    scene.meshes[0].indices[5] = 1000;
    EXPECT_NE(validationError(scene).find("scene: mesh 0 'box': index 5 is 1000, not below the vertex count 24"),
              std::string::npos)
        << validationError(scene);
}

TEST(SceneValidation, IndexCountNotAMultipleOfThreeIsAnError) {
    Scene scene = validScene();
    scene.meshes[0].indices.pop_back();
    EXPECT_NE(validationError(scene).find("is not a multiple of 3"), std::string::npos);
}

TEST(SceneValidation, MaterialIndexOutOfRangeIsAnError) {
    Scene scene = validScene();
    scene.meshes[0].materialIndex = 7;
    EXPECT_NE(validationError(scene).find("material 7 does not exist"), std::string::npos);
}

TEST(SceneValidation, NonFiniteVertexIsAnError) {
    Scene scene = validScene();
    scene.meshes[0].vertices[3].uv.x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(validationError(scene).find("vertex 3 is not finite"), std::string::npos);
}

TEST(SceneValidation, InstanceOfAMissingMeshIsAnError) {
    Scene scene = validScene();
    scene.instances[0].meshIndex = 3;
    EXPECT_NE(validationError(scene).find("instance 0: mesh 3 does not exist"), std::string::npos);
}

TEST(SceneValidation, InstanceBeyondTheCoordinateLimitIsAnError) {
    Scene scene = validScene();
    scene.instances[0].worldFromObject[3] = glm::vec4(2e10f, 0, 0, 1);
    EXPECT_NE(validationError(scene).find("world bounds reach beyond"), std::string::npos);
}

TEST(SceneValidation, TextureWhosePixelsDisagreeWithItsSizeIsAnError) {
    Scene scene = validScene();
    Texture texture;
    texture.rgba = Image(4, 4, 4);
    texture.rgba.pixels.resize(10);
    scene.textures.push_back(texture);
    EXPECT_NE(validationError(scene).find("texture 0: must be RGBA8"), std::string::npos);
}

TEST(SceneValidation, LightWithZeroDirectionIsAnError) {
    Scene scene = validScene();
    scene.lights[0].wsDirection = glm::vec3(0.0f);
    EXPECT_NE(validationError(scene).find("light 0: the direction must be a unit vector"), std::string::npos);
}

TEST(SceneValidation, MaterialWithNonFiniteRoughnessIsAnError) {
    Scene scene = validScene();
    scene.materials[0].roughness = std::numeric_limits<float>::infinity();
    EXPECT_NE(validationError(scene).find("roughness = inf is out of range"), std::string::npos);
}

TEST(SceneValidation, CameraWithNearNotBelowFarIsAnError) {
    Scene scene = validScene();
    scene.camera = makeLookAtCamera({0, 1, 5}, {0, 0, 0}, 0.8f, 10.0f, 5.0f);
    EXPECT_NE(validationError(scene).find("zFar = 5 must be greater than zNear = 10"), std::string::npos);
}

TEST(SceneValidation, CameraWithZeroFieldOfViewIsAnError) {
    Scene scene = validScene();
    scene.camera = makeLookAtCamera({0, 1, 5}, {0, 0, 0}, 0.0f);
    EXPECT_NE(validationError(scene).find("yfov = 0 must be in (0, pi)"), std::string::npos);
}

TEST(CameraView, MakingAViewOfABadCameraIsAnError) {
    Camera camera = makeLookAtCamera({0, 1, 5}, {0, 0, 0}, 0.8f);
    camera.zNear = 0.0f;
    EXPECT_THROW(makeCameraView(camera, 64, 64), Error);
    camera = makeLookAtCamera({0, 1, 5}, {0, 0, 0}, 0.8f);
    camera.worldFromView = glm::mat4(0.0f);  // would normalize zero axes into NaN
    EXPECT_THROW(makeCameraView(camera, 64, 64), Error);
}
