// SceneBuilder and the simple shapes: winding, normals, bounds, lights and cameras.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "penumbra/scene_builder.h"

using namespace penumbra;

namespace {

// Every triangle is counter-clockwise seen from the side its vertex normals point to, and the
// normals point away from `osCenter` (outward), within `tolerance` of the face normal.
void expectOutwardCounterClockwise(const Mesh& mesh, glm::vec3 osCenter, float minCosine) {
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    ASSERT_FALSE(mesh.indices.empty());
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const Vertex& a = mesh.vertices[mesh.indices[t]];
        const Vertex& b = mesh.vertices[mesh.indices[t + 1]];
        const Vertex& c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 face = glm::normalize(glm::cross(b.osPosition - a.osPosition, c.osPosition - a.osPosition));
        const glm::vec3 centroid = (a.osPosition + b.osPosition + c.osPosition) / 3.0f;
        EXPECT_GT(glm::dot(face, centroid - osCenter), 0.0f) << "triangle " << t / 3 << " faces inward";
        for (const Vertex* v : {&a, &b, &c}) {
            EXPECT_NEAR(glm::length(v->osNormal), 1.0f, 1e-4f);
            EXPECT_GT(glm::dot(face, v->osNormal), minCosine) << "triangle " << t / 3;
        }
    }
}

}  // namespace

TEST(SceneBuilder, BoxHasFlatOutwardFacesAndHalfExtents) {
    const Mesh box = makeBoxMesh({1.0f, 2.0f, 3.0f}, 0);
    EXPECT_EQ(box.vertices.size(), 24u);
    EXPECT_EQ(box.indices.size(), 36u);
    expectOutwardCounterClockwise(box, glm::vec3(0.0f), 0.9999f);
    Aabb bounds;
    for (const Vertex& v : box.vertices) bounds.extend(v.osPosition);
    EXPECT_EQ(bounds.min, glm::vec3(-1, -2, -3));
    EXPECT_EQ(bounds.max, glm::vec3(1, 2, 3));
}

TEST(SceneBuilder, BoxFacesHaveFullUvRange) {
    const Mesh box = makeBoxMesh(glm::vec3(1.0f), 0);
    for (size_t face = 0; face < 6; ++face) {
        glm::vec2 uvMin(1e9f), uvMax(-1e9f);
        for (size_t i = 0; i < 4; ++i) {
            uvMin = glm::min(uvMin, box.vertices[face * 4 + i].uv);
            uvMax = glm::max(uvMax, box.vertices[face * 4 + i].uv);
        }
        EXPECT_EQ(uvMin, glm::vec2(0.0f));
        EXPECT_EQ(uvMax, glm::vec2(1.0f));
    }
}

TEST(SceneBuilder, SphereVerticesLieOnItsRadiusWithOutwardNormals) {
    const Mesh sphere = makeSphereMesh(2.0f, 3, 16, 8);
    EXPECT_EQ(sphere.materialIndex, 3u);
    for (const Vertex& v : sphere.vertices) {
        EXPECT_NEAR(glm::length(v.osPosition), 2.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(v.osNormal, glm::normalize(v.osPosition)), 1.0f, 1e-5f);
    }
    expectOutwardCounterClockwise(sphere, glm::vec3(0.0f), 0.9f);
}

TEST(SceneBuilder, PlaneLiesAtYZeroFacingUp) {
    const Mesh plane = makePlaneMesh({4.0f, 6.0f}, 0, 2.0f);
    ASSERT_EQ(plane.indices.size(), 6u);
    for (const Vertex& v : plane.vertices) {
        EXPECT_EQ(v.osPosition.y, 0.0f);
        EXPECT_EQ(v.osNormal, glm::vec3(0, 1, 0));
        EXPECT_LE(std::max(v.uv.x, v.uv.y), 2.0f);
    }
    expectOutwardCounterClockwise(plane, glm::vec3(0, -1, 0), 0.9999f);
    EXPECT_EQ(std::abs(plane.vertices[0].osPosition.x), 2.0f);
    EXPECT_EQ(std::abs(plane.vertices[0].osPosition.z), 3.0f);
}

TEST(SceneBuilder, QuadFacesPlusZWithUvOriginTopLeft) {
    const Mesh quad = makeQuadMesh({2.0f, 1.0f}, 0);
    expectOutwardCounterClockwise(quad, glm::vec3(0, 0, -1), 0.9999f);
    for (const Vertex& v : quad.vertices) {
        EXPECT_EQ(v.osPosition.z, 0.0f);
        EXPECT_FLOAT_EQ(v.uv.x, v.osPosition.x / 2.0f + 0.5f);  // u grows to +X
        EXPECT_FLOAT_EQ(v.uv.y, 0.5f - v.osPosition.y);         // v grows downwards: (0,0) top-left
    }
}

TEST(SceneBuilder, CylinderSpansZeroToHeightWithOutwardSurface) {
    const Mesh cylinder = makeCylinderMesh(0.5f, 3.0f, 0, 12);
    Aabb bounds;
    for (const Vertex& v : cylinder.vertices) bounds.extend(v.osPosition);
    EXPECT_NEAR(bounds.min.y, 0.0f, 1e-6f);
    EXPECT_NEAR(bounds.max.y, 3.0f, 1e-6f);
    EXPECT_NEAR(bounds.max.x, 0.5f, 1e-6f);
    expectOutwardCounterClockwise(cylinder, glm::vec3(0, 1.5f, 0), 0.8f);
}

TEST(SceneBuilder, BuildComputesMeshInstanceAndSceneBounds) {
    SceneBuilder builder;
    const uint32_t mesh = builder.addMesh(makeBoxMesh(glm::vec3(1.0f), 0));
    builder.addInstance(mesh, glm::translate(glm::mat4(1.0f), {10, 0, 0}));
    builder.addInstance(mesh, glm::scale(glm::mat4(1.0f), {2, 2, 2}), false, "big");
    const Scene scene = builder.build();
    EXPECT_EQ(scene.meshes[0].osBounds.max, glm::vec3(1.0f));
    EXPECT_EQ(scene.instances[0].wsBounds.min, glm::vec3(9, -1, -1));
    EXPECT_EQ(scene.instances[1].wsBounds.max, glm::vec3(2, 2, 2));
    EXPECT_FALSE(scene.instances[1].castShadows);
    EXPECT_EQ(scene.instances[1].nodeName, "big");
    EXPECT_EQ(scene.wsBounds.min, glm::vec3(-2, -2, -2));
    EXPECT_EQ(scene.wsBounds.max, glm::vec3(11, 2, 2));
}

TEST(SceneBuilder, BuildAddsDefaultMaterialWhenThereIsNone) {
    SceneBuilder builder;
    builder.addInstance(builder.addMesh(makeQuadMesh({1, 1}, 0)), glm::mat4(1.0f));
    const Scene scene = builder.build();
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
}

TEST(SceneBuilder, BuildKeepsGivenMaterialsAndTexturesInOrder) {
    SceneBuilder builder;
    Material a, b;
    a.name = "a";
    b.name = "b";
    EXPECT_EQ(builder.addMaterial(a), 0u);
    EXPECT_EQ(builder.addMaterial(b), 1u);
    Texture texture;
    texture.rgba = Image(2, 2, 4, 255);
    EXPECT_EQ(builder.addTexture(texture), 0u);
    const Scene scene = builder.build();
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[1].name, "b");
    EXPECT_EQ(scene.textures.size(), 1u);
}

TEST(SceneBuilder, LightHelpersNormalizeDirectionsAndSetNearPlaneDefaults) {
    const Light sun = makeDirectionalLight({0, -2, 0}, 3.0f, {1, 0.5f, 0.5f});
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_EQ(sun.wsDirection, glm::vec3(0, -1, 0));
    EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
    EXPECT_FLOAT_EQ(sun.shadowNearPlane, 0.0f);
    const Light spot = makeSpotLight({0, 5, 0}, {0, 0, -3}, 100.0f, 20.0f, 0.6f, 0.4f);
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.wsDirection, glm::vec3(0, 0, -1));
    EXPECT_FLOAT_EQ(spot.range, 20.0f);
    EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.6f);
    EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.4f);
    EXPECT_FLOAT_EQ(spot.shadowNearPlane, 0.1f);
    const Light point = makePointLight({1, 2, 3}, 50.0f, 10.0f);
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_EQ(point.wsPosition, glm::vec3(1, 2, 3));
}

TEST(SceneBuilder, LookAtCameraLooksAlongMinusZTowardsTheTarget) {
    const Camera camera = makeLookAtCamera({0, 6, 16}, {0, 1, 0}, 0.9f);
    const glm::vec3 wsEye(camera.worldFromView[3]);
    const glm::vec3 wsForward = -glm::vec3(camera.worldFromView[2]);
    EXPECT_NEAR(glm::length(wsEye - glm::vec3(0, 6, 16)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(wsForward, glm::normalize(glm::vec3(0, -5, -16))), 1.0f, 1e-5f);
    EXPECT_GT(camera.worldFromView[1].y, 0.0f);  // +Y of the view is up in the world
    EXPECT_TRUE(std::isinf(camera.zFar));
}

TEST(SceneBuilder, LookAtCameraStraightDownIsWellDefined) {
    const Camera camera = makeLookAtCamera({0, 10, 0}, {0, 0, 0}, 0.9f);
    const glm::vec3 wsForward = -glm::vec3(camera.worldFromView[2]);
    EXPECT_NEAR(wsForward.y, -1.0f, 1e-5f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(camera.worldFromView[c][r]));
}
