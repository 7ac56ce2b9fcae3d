// The per-instance GPU record (scene_structs.h InstanceData): what the shaders read per instance, 64
// bytes, from which they rebuild worldFromObject exactly and derive the normals' transform. The
// functions are the shaders' own (scene_structs.h is compiled as C++ and GLSL alike).
#include <cmath>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "scene_structs.h"

using namespace penumbra;

namespace {

constexpr float kNormalTolerance = 1e-5f;

// A rotation about a skew axis, a non-uniform scale (1:6:3.4) and a translation.
glm::mat4 rotatedNonUniformScale() {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), {3.0f, -2.0f, 7.5f});
    m = glm::rotate(m, 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f)));
    return glm::scale(m, {0.5f, 3.0f, 1.7f});
}

// Normals spread over the sphere, none along an axis.
const glm::vec3 kNormals[] = {{0.0f, 0.0f, 1.0f}, {0.6f, 0.8f, 0.0f}, {-0.3f, 0.5f, 0.81f}, {0.57735f, -0.57735f, 0.57735f}};

void expectSameDirections(const glm::mat3& actual, const glm::mat3& expected) {
    for (const glm::vec3& n : kNormals) {
        const glm::vec3 a = glm::normalize(actual * n), e = glm::normalize(expected * n);
        EXPECT_NEAR(glm::distance(a, e), 0.0f, kNormalTolerance) << "normal (" << n.x << ", " << n.y << ", " << n.z << ")";
    }
}

}  // namespace

TEST(InstanceData, PacksToSixtyFourBytes) {
    const gpu_data::InstanceData packed = packInstanceData(rotatedNonUniformScale(), 7);
    EXPECT_EQ(sizeof(packed), 64u) << "was 144: two mat4, the material and padding";
}

TEST(InstanceData, RebuildsWorldFromObjectExactlyAndKeepsTheMaterial) {
    const glm::mat4 worldFromObject = rotatedNonUniformScale();
    const gpu_data::InstanceData packed = packInstanceData(worldFromObject, 7);
    EXPECT_EQ(gpu_data::instanceWorldFromObject(packed), worldFromObject);
    EXPECT_EQ(packed.materialIndex, 7u);
}

TEST(InstanceData, NormalTransformIsTheInverseTransposeForANonUniformScaleAndRotation) {
    const glm::mat4 worldFromObject = rotatedNonUniformScale();
    const glm::mat3 normalFromObject = gpu_data::instanceNormalFromObject(packInstanceData(worldFromObject, 0));
    expectSameDirections(normalFromObject, glm::transpose(glm::inverse(glm::mat3(worldFromObject))));
}

TEST(InstanceData, NormalTransformOfAMirroredInstanceKeepsTheNormalsOutward) {
    const glm::mat4 mirrored = glm::scale(rotatedNonUniformScale(), {-1.0f, 1.0f, 1.0f});
    const glm::mat3 normalFromObject = gpu_data::instanceNormalFromObject(packInstanceData(mirrored, 0));
    expectSameDirections(normalFromObject, glm::transpose(glm::inverse(glm::mat3(mirrored))));
}

TEST(InstanceData, NormalTransformOfAZeroScaleStaysFinite) {
    const glm::mat4 flattened = glm::scale(rotatedNonUniformScale(), {1.0f, 0.0f, 1.0f});
    const glm::mat3 normalFromObject = gpu_data::instanceNormalFromObject(packInstanceData(flattened, 0));
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            EXPECT_TRUE(std::isfinite(normalFromObject[column][row])) << "column " << column << ", row " << row;
}
