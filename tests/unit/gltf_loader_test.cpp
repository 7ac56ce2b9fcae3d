// Loading real sample models and the glTF features the renderer relies on.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;

namespace {

const std::string kSamples = "/usr/share/assimp/models/glTF2/";

void expectVec3Near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

#define REQUIRE_SAMPLE(path) \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "sample model not installed: " << (path)

}  // namespace

TEST(GltfLoader, LoadsTexturedBoxWithDecodedTexture) {
    const std::string path = kSamples + "BoxTextured-glTF/BoxTextured.gltf";
    REQUIRE_SAMPLE(path);
    const Scene scene = loadGltfScene(path);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].vertices.size(), 24u);
    EXPECT_EQ(scene.meshes[0].indices.size(), 36u);
    ASSERT_EQ(scene.materials.size(), 1u);  // every primitive has a material: no default appended
    EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
    EXPECT_FLOAT_EQ(scene.materials[0].metallic, 0.0f);
    ASSERT_EQ(scene.textures.size(), 1u);
    const Image& rgba = scene.textures[0].rgba;
    EXPECT_GT(rgba.width, 0u);
    EXPECT_GT(rgba.height, 0u);
    EXPECT_EQ(rgba.channels, 4u);
    EXPECT_EQ(rgba.pixels.size(), size_t(rgba.width) * rgba.height * 4);
    EXPECT_EQ(scene.instances.size(), 1u);
    EXPECT_TRUE(scene.wsBounds.valid());
}

TEST(GltfLoader, ReadsTheTexturesSampler) {
    const std::string path = kSamples + "BoxTextured-glTF/BoxTextured.gltf";
    REQUIRE_SAMPLE(path);
    const Scene scene = loadGltfScene(path);
    const TextureSampler& sampler = scene.textures.at(0).sampler;
    // magFilter 9729, minFilter 9986 (NEAREST_MIPMAP_LINEAR), wrapS 33648, wrapT 33071.
    EXPECT_EQ(sampler.magFilter, TextureFilter::Linear);
    EXPECT_EQ(sampler.minFilter, TextureFilter::Nearest);
    EXPECT_EQ(sampler.mipmaps, MipmapMode::Linear);
    EXPECT_EQ(sampler.wrapS, TextureWrap::MirroredRepeat);
    EXPECT_EQ(sampler.wrapT, TextureWrap::ClampToEdge);
}

TEST(GltfLoader, DecodesTextureStoredInGlbBufferView) {
    const std::string path = kSamples + "BoxTextured-glTF-Binary/BoxTextured.glb";
    REQUIRE_SAMPLE(path);
    const Scene scene = loadGltfScene(path);
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_GT(scene.textures[0].rgba.width, 0u);
}

TEST(GltfLoader, LoadsBinaryEngineWithAllPrimitivesAndInstances) {
    const std::string path = kSamples + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    REQUIRE_SAMPLE(path);
    const Scene scene = loadGltfScene(path);
    EXPECT_EQ(scene.meshes.size(), 34u);      // 29 meshes with 34 triangle primitives
    EXPECT_EQ(scene.instances.size(), 115u);  // (node, primitive) pairs of the default scene
    EXPECT_EQ(scene.materials.size(), 34u);
    size_t vertexCount = 0;
    for (const Mesh& mesh : scene.meshes) vertexCount += mesh.vertices.size();
    EXPECT_EQ(vertexCount, 55843u);
    EXPECT_TRUE(scene.camera.has_value());
    for (const Instance& instance : scene.instances) EXPECT_TRUE(instance.wsBounds.valid());
}

TEST(GltfLoader, GeneratesFlatNormalsWhenNormalsAreMissing) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const Scene scene = loadGltfScene(gltf.write(dir, "triangle"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.meshes[0].vertices.size(), 3u);
    for (const Vertex& v : scene.meshes[0].vertices) expectVec3Near(v.osNormal, {0, 0, 1});
}

TEST(GltfLoader, ReadsNonIndexedPrimitivesAsSequentialTriangles) {
    TempDir dir;
    TestGltf gltf;
    const int positions = gltf.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}})}});
    const Scene scene = loadGltfScene(gltf.write(dir, "sequential"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(GltfLoader, FlattensNodeHierarchyWithTranslationRotationScale) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    const int child = gltf.addNode({{"name", "child"}, {"mesh", mesh}, {"translation", {0, 1, 0}}}, false);
    // Parent: translate (1,0,0), rotate 90 degrees about +Z, scale 2: child origin -> (1,0,0) + R(0,2,0) = (-1,0,0).
    const float s = std::sqrt(0.5f);
    gltf.addNode({{"name", "parent"}, {"translation", {1, 0, 0}}, {"rotation", {0, 0, s, s}}, {"scale", {2, 2, 2}},
                  {"children", {child}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "hierarchy"));
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_EQ(scene.instances[0].nodeName, "child");
    expectVec3Near(glm::vec3(scene.instances[0].worldFromObject[3]), {-1, 0, 0});
    expectVec3Near(glm::vec3(scene.instances[0].worldFromObject * glm::vec4(1, 0, 0, 1)), {-1, 2, 0});
}

TEST(GltfLoader, UsesNodeMatrixWhenGiven) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()},
                  {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1}}});  // column-major: translation last
    const Scene scene = loadGltfScene(gltf.write(dir, "matrix"));
    ASSERT_EQ(scene.instances.size(), 1u);
    expectVec3Near(scene.instances[0].wsBounds.min, {5, 6, 7});
    expectVec3Near(scene.instances[0].wsBounds.max, {6, 7, 7});
}

TEST(GltfLoader, CreatesOneInstancePerNodeReferencingAMesh) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    gltf.addNode({{"mesh", mesh}});
    gltf.addNode({{"mesh", mesh}, {"translation", {3, 0, 0}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "shared"));
    EXPECT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 2u);
    EXPECT_EQ(scene.instances[0].meshIndex, scene.instances[1].meshIndex);
    EXPECT_FLOAT_EQ(scene.wsBounds.max.x, 4.0f);
}

TEST(GltfLoader, UsesAllRootNodesWhenThereAreNoScenes) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    gltf.addNode({{"mesh", mesh}});
    gltf.addNode({{"mesh", mesh}});
    gltf.doc.erase("scenes");
    gltf.doc.erase("scene");
    EXPECT_EQ(loadGltfScene(gltf.write(dir, "noscenes")).instances.size(), 2u);
}

TEST(GltfLoader, SkipsNonTrianglePrimitivesWithAWarning) {
    TempDir dir;
    TestGltf gltf;
    const int positions = gltf.addVec3({{0, 0, 0}, {1, 0, 0}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}, {"mode", 1}})}});  // LINES
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const Scene scene = loadGltfScene(gltf.write(dir, "lines"));
    EXPECT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 1u);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("mode 1"), std::string::npos) << scene.warnings[0];
}

TEST(GltfLoader, EmptySceneIsValid) {
    TempDir dir;
    TestGltf gltf;
    const Scene scene = loadGltfScene(gltf.write(dir, "empty"));
    EXPECT_TRUE(scene.instances.empty());
    EXPECT_FALSE(scene.wsBounds.valid());
    EXPECT_FALSE(scene.materials.empty());
}

TEST(GltfLoader, CameraNodeNamedCameraWinsOverTheFirstCamera) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.2}, {"zfar", 50}}}}};
    gltf.addNode({{"name", "first"}, {"camera", 0}});
    gltf.addNode({{"name", "camera"}, {"camera", 1}, {"translation", {0, 2, 5}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "cameras"));
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->name, "camera");
    EXPECT_FLOAT_EQ(scene.camera->yfov, 0.9f);
    EXPECT_FLOAT_EQ(scene.camera->zNear, 0.2f);
    EXPECT_FLOAT_EQ(scene.camera->zFar, 50.0f);
    expectVec3Near(glm::vec3(scene.camera->worldFromView[3]), {0, 2, 5});
}

TEST(GltfLoader, FirstCameraNodeIsUsedWhenNoneIsNamedCamera) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.2}}}}};
    gltf.addNode({{"name", "a"}, {"camera", 0}});
    gltf.addNode({{"name", "b"}, {"camera", 1}});
    const Scene scene = loadGltfScene(gltf.write(dir, "cameras"));
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->name, "a");
    EXPECT_TRUE(std::isinf(scene.camera->zFar));  // no zfar: infinite projection
}

TEST(GltfLoader, EveryPerspectiveCameraIsListedInNodeOrder) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.2}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", -1.0}}}}};
    gltf.addNode({{"name", "a"}, {"camera", 0}});
    gltf.addNode({{"name", "camera"}, {"camera", 1}, {"translation", {0, 2, 5}}});
    gltf.addNode({{"name", "bad"}, {"camera", 2}});  // znear < 0: not offered, and not an error
    const Scene scene = loadGltfScene(gltf.write(dir, "cameras"));
    ASSERT_EQ(scene.cameras.size(), 2u);
    EXPECT_EQ(scene.cameras[0].name, "a");
    EXPECT_EQ(scene.cameras[1].name, "camera");
    EXPECT_FLOAT_EQ(scene.cameras[1].yfov, 0.9f);
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->name, "camera");
}

TEST(GltfLoader, LightDirectionIsNodeMinusZInWorldSpace) {
    TempDir dir;
    TestGltf gltf;
    gltf.addLight({{"type", "directional"}, {"intensity", 3.0}});
    const float s = std::sqrt(0.5f);
    // -90 degrees about +X turns -Z into -Y: the light shines straight down.
    gltf.addNode({{"rotation", {-s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "sun"));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, LightType::Directional);
    EXPECT_FLOAT_EQ(scene.lights[0].intensity, 3.0f);
    expectVec3Near(scene.lights[0].wsDirection, {0, -1, 0});
}

TEST(GltfLoader, SpotLightTakesPositionAndConesFromItsNodeAndDefinition) {
    TempDir dir;
    TestGltf gltf;
    gltf.addLight({{"type", "spot"}, {"name", "Spot"}, {"color", {1, 0.5, 0.25}}, {"intensity", 40}, {"range", 12},
                   {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}});
    const int lightNode = gltf.addNode({{"scale", {3, 3, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                       false);
    gltf.addNode({{"translation", {1, 4, 2}}, {"children", {lightNode}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "spot"));
    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& light = scene.lights[0];
    EXPECT_EQ(light.type, LightType::Spot);
    EXPECT_EQ(light.name, "Spot");
    expectVec3Near(light.color, {1, 0.5f, 0.25f});
    EXPECT_FLOAT_EQ(light.range, 12.0f);
    EXPECT_FLOAT_EQ(light.innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(light.outerConeAngle, 0.5f);
    expectVec3Near(light.wsPosition, {1, 4, 2});
    expectVec3Near(light.wsDirection, {0, 0, -1});  // unit despite the node's scale
}

TEST(GltfLoader, KeepsLightsInExtensionOrderAndUnplacedLightsAtTheOrigin) {
    TempDir dir;
    TestGltf gltf;
    gltf.addLight({{"type", "point"}, {"name", "unplaced"}});
    gltf.addLight({{"type", "directional"}, {"name", "placed"}});
    gltf.addNode({{"translation", {0, 5, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    const Scene scene = loadGltfScene(gltf.write(dir, "order"));
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].name, "unplaced");
    EXPECT_EQ(scene.lights[1].name, "placed");
    expectVec3Near(scene.lights[0].wsPosition, {0, 0, 0});
    expectVec3Near(scene.lights[0].wsDirection, {0, 0, -1});
    expectVec3Near(scene.lights[1].wsPosition, {0, 5, 0});
}

TEST(GltfLoader, ReadsMaterialAlphaModesUnlitAndDoubleSided) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["materials"] = {
        {{"name", "opaque"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}}, {"roughnessFactor", 0.3}}}},
        {{"name", "mask"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.3}, {"doubleSided", true}},
        {{"name", "blend"}, {"alphaMode", "BLEND"}, {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}}};
    const Scene scene = loadGltfScene(gltf.write(dir, "materials"));
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.materials[0].baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1));
    EXPECT_FLOAT_EQ(scene.materials[0].roughness, 0.3f);
    EXPECT_EQ(scene.materials[0].alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(scene.materials[0].shadows, MaterialShadowMode::On);
    EXPECT_EQ(scene.materials[1].alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(scene.materials[1].alphaCutoff, 0.3f);
    EXPECT_TRUE(scene.materials[1].doubleSided);
    EXPECT_EQ(scene.materials[1].shadows, MaterialShadowMode::Clip);
    EXPECT_EQ(scene.materials[2].alphaMode, AlphaMode::Blend);
    EXPECT_EQ(scene.materials[2].shadows, MaterialShadowMode::Dither);
    EXPECT_TRUE(scene.materials[2].unlit);
    EXPECT_FALSE(scene.materials[0].unlit);
}

TEST(GltfLoader, AppendsDefaultMaterialForPrimitivesWithoutOne) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["materials"] = {{{"name", "unused"}}};
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const Scene scene = loadGltfScene(gltf.write(dir, "default_material"));
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.meshes[0].materialIndex, 1u);
    EXPECT_EQ(scene.materials[1].name, "default");
}
