// glTF input at and past the limits: each case is a one-line Error naming the file
// and the object, or a documented fallback with a warning; never a crash, a NaN or a silent change.
#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using penumbra::testing::expectLoadError;
using penumbra::testing::hasWarning;
using penumbra::testing::readFile;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;
using penumbra::testing::writeFile;

namespace {

// A triangle mesh under a node with `node`'s extra members (rotation, scale, ...).
std::string triangleUnder(const TempDir& dir, const std::string& name, nlohmann::json node) {
    TestGltf gltf;
    node["mesh"] = gltf.addTriangleMesh();
    gltf.addNode(node);
    return gltf.write(dir, name);
}

// A directional light placed by a node with `node`'s members.
std::string lightUnder(const TempDir& dir, const std::string& name, nlohmann::json node, const char* type) {
    TestGltf gltf;
    gltf.addLight({{"type", type}});
    node["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    gltf.addNode(node);
    return gltf.write(dir, name);
}

bool allFinite(const Mesh& mesh) {
    for (const Vertex& v : mesh.vertices)
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(v.osNormal[i]) || !std::isfinite(v.osPosition[i])) return false;
    return true;
}

}  // namespace

TEST(GltfLimits, ZeroQuaternionIsAnError) {
    TempDir dir;
    expectLoadError(triangleUnder(dir, "zero_rotation", {{"name", "spin"}, {"rotation", {0, 0, 0, 0}}}),
                    "node 0 'spin': rotation [0.000000, 0.000000, 0.000000, 0.000000] is not a unit quaternion");
}

TEST(GltfLimits, LightWithZeroQuaternionIsAnError) {
    TempDir dir;
    expectLoadError(lightUnder(dir, "light_zero_rotation", {{"rotation", {0, 0, 0, 0}}}, "directional"),
                    "is not a unit quaternion");
}

TEST(GltfLimits, NonUnitQuaternionIsNormalizedWithAWarning) {
    TempDir dir;
    const Scene scene = loadGltfScene(triangleUnder(dir, "long_rotation", {{"rotation", {0, 0, 0, 2}}}));
    EXPECT_TRUE(hasWarning(scene, "rotation has length 2.000000, normalized"));
    const glm::mat4& m = scene.instances.at(0).worldFromObject;
    EXPECT_NEAR(m[0][0], 1.0f, 1e-6f);  // the identity rotation, not a scale of 4
    EXPECT_NEAR(m[1][1], 1.0f, 1e-6f);
}

TEST(GltfLimits, DirectionalLightOnAZeroScaleNodeIsAnError) {
    TempDir dir;
    expectLoadError(lightUnder(dir, "flat_sun", {{"name", "sun"}, {"scale", {1, 1, 0}}}, "directional"),
                    "node 0 'sun': the light's direction is undefined");
}

TEST(GltfLimits, PointLightOnAZeroScaleNodeIsPlaced) {
    TempDir dir;
    const Scene scene =
        loadGltfScene(lightUnder(dir, "flat_point", {{"scale", {0, 0, 0}}, {"translation", {1, 2, 3}}}, "point"));
    EXPECT_EQ(scene.lights.at(0).wsPosition, glm::vec3(1, 2, 3));
}

TEST(GltfLimits, MeshOnAZeroScaleNodeIsNotDrawnAndSaysSo) {
    TempDir dir;
    const Scene scene = loadGltfScene(triangleUnder(dir, "hidden", {{"name", "hidden"}, {"scale", {0, 0, 0}}}));
    EXPECT_TRUE(scene.instances.empty());
    EXPECT_TRUE(hasWarning(scene, "node 0 'hidden': the world transform is singular"));
}

TEST(GltfLimits, CameraOnAZeroScaleNodeIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    gltf.addNode({{"camera", 0}, {"scale", {0, 1, 1}}});
    expectLoadError(gltf.write(dir, "flat_camera"), "the transform is degenerate");
}

TEST(GltfLimits, ZeroFieldOfViewIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}}};
    gltf.addNode({{"camera", 0}});
    expectLoadError(gltf.write(dir, "no_fov"), "yfov must be in (0, pi)");
}

TEST(GltfLimits, FarPlaneNotBeyondNearPlaneIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 2.0}, {"zfar", 1.0}}}}};
    gltf.addNode({{"camera", 0}});
    expectLoadError(gltf.write(dir, "inverted_planes"), "zfar must be greater than znear");
}

TEST(GltfLimits, DegenerateTrianglesLoadWithFiniteNormals) {
    TempDir dir;
    TestGltf gltf;
    // A zero-area triangle (three equal points) and a collinear one, without normals: flat normals
    // are generated, and a degenerate face gets +Y rather than NaN.
    const int positions = gltf.addVec3({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}})}});
    const Scene scene = loadGltfScene(gltf.write(dir, "degenerate"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices.size(), 6u);
    EXPECT_TRUE(allFinite(scene.meshes[0]));
    EXPECT_EQ(scene.meshes[0].vertices[0].osNormal, glm::vec3(0, 1, 0));
}

TEST(GltfLimits, ZeroNormalsAreReplacedAndSaySo) {
    TempDir dir;
    TestGltf gltf;
    const int positions = gltf.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int normals = gltf.addVec3({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}})}});
    const Scene scene = loadGltfScene(gltf.write(dir, "zero_normals"));
    EXPECT_TRUE(hasWarning(scene, "NORMAL: 2 zero or non-finite normals replaced by +Y"));
    EXPECT_TRUE(allFinite(scene.meshes.at(0)));
}

TEST(GltfLimits, NonFiniteTexcoordIsAnError) {
    TempDir dir;
    TestGltf gltf;
    const float inf = std::numeric_limits<float>::infinity();
    const int positions = gltf.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::vector<glm::vec2> uv = {{0, 0}, {inf, 0}, {0, 1}};
    const int uvs = gltf.addAccessor(uv.data(), uv.size(), 8, 5126, "VEC2");
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}}})}});
    expectLoadError(gltf.write(dir, "inf_uv"), "TEXCOORD_0: vertex 1 is not finite");
}

TEST(GltfLimits, VertexBeyondTheCoordinateLimitIsAnError) {
    // fuzz_gltf's first finding: such a file loaded, then the renderer's scene check refused it.
    TempDir dir;
    TestGltf gltf;
    const int positions = gltf.addVec3({{0, 0, 0}, {3e30f, 0, 0}, {0, 1, 0}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}})}});
    expectLoadError(gltf.write(dir, "huge_vertex"), "POSITION: vertex 1 lies beyond 1e10");
}

TEST(GltfLimits, NodeScaleThatCarriesGeometryPastTheLimitIsAnError) {
    TempDir dir;
    expectLoadError(triangleUnder(dir, "huge_scale", {{"scale", {1e12, 1, 1}}}), "world bounds reach beyond");
}

TEST(GltfLimits, MetallicFactorOutOfRangeIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["materials"] = {{{"name", "shiny"}, {"pbrMetallicRoughness", {{"metallicFactor", 2.0}}}}};
    expectLoadError(gltf.write(dir, "metallic"), "material 0 'shiny': metallic = 2 is out of range (allowed 0..1)");
}

TEST(GltfLimits, BaseColorFactorOutOfRangeIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.5, 1, 1, 1}}}}}};
    expectLoadError(gltf.write(dir, "color"), "baseColorFactor = 1.5 is out of range");
}

TEST(GltfLimits, AccessorWithoutBufferViewIsAnError) {
    TempDir dir;
    TestGltf gltf;
    // A count of 2^40 zeros: refused before any allocation.
    gltf.doc["accessors"].push_back({{"componentType", 5126}, {"count", 1ull << 40}, {"type", "VEC3"}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", 0}}}})}});
    expectLoadError(gltf.write(dir, "no_view"), "accessor 0 has no bufferView");
}

TEST(GltfLimits, AccessorOffsetThatWrapsAroundIsAnError) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    // byteOffset + stride * (count - 1) wraps a 64-bit sum back below the view's length.
    gltf.doc["accessors"][0]["byteOffset"] = 18446744073709551600ull;
    gltf.addNode({{"mesh", mesh}});
    expectLoadError(gltf.write(dir, "wrap"), "reads past the end of its bufferView");
}

TEST(GltfLimits, DirectoryGivenAsTheSceneIsAnError) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("folder.gltf"));
    expectLoadError(dir.file("folder.gltf"), "cannot open file (it is a directory)");
}

TEST(GltfLimits, BufferUriNamingADirectoryIsAnError) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const std::string path = gltf.write(dir, "dirbuffer");
    std::filesystem::remove(dir.file("dirbuffer.bin"));
    std::filesystem::create_directories(dir.file("dirbuffer.bin"));
    expectLoadError(path, "dirbuffer.bin");
}

TEST(GltfLimits, BufferUriLinkedToADeviceIsAnErrorNotAnEndlessRead) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const std::string path = gltf.write(dir, "device");
    std::filesystem::remove(dir.file("device.bin"));
    std::filesystem::create_symlink("/dev/zero", dir.file("device.bin"));  // an endless read, were it read
    expectLoadError(path, "'device.bin' resolves to /dev/zero, outside the asset root");
}

TEST(GltfLimits, GltfInMemoryReadsNoExternalFile) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const std::string text = readFile(gltf.write(dir, "external"));
    const std::string bin = dir.file("external.bin");
    nlohmann::json doc = nlohmann::json::parse(text);
    doc["buffers"][0]["uri"] = bin;  // an absolute path that exists
    const std::string bytes = doc.dump();
    try {
        loadGltfSceneFromMemory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "memory.gltf");
        ADD_FAILURE() << "an external file was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is not read"), std::string::npos) << e.what();
    }
}
