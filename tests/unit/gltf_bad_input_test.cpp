// Bad glTF input ends in one penumbra::Error line naming the file, never in a crash.
#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;
using penumbra::testing::readFile;
using penumbra::testing::writeFile;
using penumbra::testing::expectLoadError;

namespace {

const std::string kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

}  // namespace

TEST(GltfBadInput, MissingFile) {
    TempDir dir;
    expectLoadError(dir.file("nothing.gltf"), "cannot open");
}

TEST(GltfBadInput, TruncatedGlb) {
    if (!std::filesystem::exists(kEngine)) GTEST_SKIP() << "sample model not installed";
    TempDir dir;
    const std::string bytes = readFile(kEngine);
    for (size_t size : {size_t(10), size_t(100), bytes.size() / 2, bytes.size() - 4}) {
        const std::string path = dir.file("truncated_" + std::to_string(size) + ".glb");
        writeFile(path, bytes.substr(0, size));
        expectLoadError(path, "invalid glTF");
    }
}

TEST(GltfBadInput, UnknownSamplerFilterNamesTheSampler) {
    const std::string box = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    if (!std::filesystem::exists(box)) GTEST_SKIP() << "sample model not installed";
    TempDir dir;
    std::string text = readFile(box);
    const size_t at = text.find("\"minFilter\": 9986");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 17, "\"minFilter\": 1234");
    const std::string path = dir.file("BoxTextured.gltf");
    writeFile(path, text);
    std::filesystem::copy(std::filesystem::path(box).parent_path() / "BoxTextured0.bin", dir.file("BoxTextured0.bin"));
    std::filesystem::copy(std::filesystem::path(box).parent_path() / "CesiumLogoFlat.png", dir.file("CesiumLogoFlat.png"));
    expectLoadError(path, "sampler 0: minFilter 1234");
}

TEST(GltfBadInput, MalformedJson) {
    TempDir dir;
    const std::string path = dir.file("malformed.gltf");
    writeFile(path, "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {");
    expectLoadError(path, "invalid glTF");
}

TEST(GltfBadInput, MissingExternalBuffer) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    const std::string path = gltf.write(dir, "nobin");
    std::filesystem::remove(dir.file("nobin.bin"));
    expectLoadError(path, "nobin.bin");
}

TEST(GltfBadInput, AccessorIndexOutOfRange) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", 99}}}})}});
    expectLoadError(gltf.write(dir, "accessor"), "accessor 99 is out of range");
}

TEST(GltfBadInput, BufferViewIndexOutOfRange) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    gltf.doc["accessors"][0]["bufferView"] = 42;
    gltf.addNode({{"mesh", mesh}});
    expectLoadError(gltf.write(dir, "view"), "bufferView 42");
}

TEST(GltfBadInput, AccessorReadingPastItsBuffer) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    gltf.doc["accessors"][0]["count"] = 1000;
    gltf.addNode({{"mesh", mesh}});
    expectLoadError(gltf.write(dir, "past"), "reads past the end");
}

TEST(GltfBadInput, IndexNotBelowVertexCount) {
    TempDir dir;
    TestGltf gltf;
    const int positions = gltf.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int indices = gltf.addIndices16({0, 1, 3});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}, {"indices", indices}})}});
    expectLoadError(gltf.write(dir, "index"), "not below the vertex count 3");
}

TEST(GltfBadInput, InfiniteNodeTransform) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"name", "Far"}, {"mesh", gltf.addTriangleMesh()}, {"translation", {1e300, 0, 0}}});
    expectLoadError(gltf.write(dir, "transform"), "node 0 'Far': transform is not finite");
}

TEST(GltfBadInput, NanVertexPosition) {
    TempDir dir;
    TestGltf gltf;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const int positions = gltf.addVec3({{0, 0, 0}, {nan, 0, 0}, {0, 1, 0}});
    gltf.addNode({{"mesh", gltf.addMesh({{"attributes", {{"POSITION", positions}}}})}});
    expectLoadError(gltf.write(dir, "nan"), "vertex 1 is not finite");
}

TEST(GltfBadInput, NonFiniteLightIntensityAndColor) {
    TempDir dir;
    TestGltf intensity;
    intensity.addLight({{"type", "point"}, {"intensity", 1e300}});
    expectLoadError(intensity.write(dir, "intensity"), "light 0: intensity");
    TestGltf color;
    color.addLight({{"type", "point"}, {"color", {1, 1e300, 1}}});
    expectLoadError(color.write(dir, "color"), "light 0: color");
}

TEST(GltfBadInput, TextureThatFailsToDecode) {
    TempDir dir;
    TestGltf gltf;
    writeFile(dir.file("broken.png"), "this is not a png at all");
    gltf.doc["images"] = {{{"uri", "broken.png"}}};
    gltf.doc["textures"] = {{{"source", 0}}};
    expectLoadError(gltf.write(dir, "texture"), "image 0");
}

TEST(GltfBadInput, TextureFileMissing) {
    TempDir dir;
    TestGltf gltf;
    gltf.doc["images"] = {{{"uri", "absent.png"}}};
    gltf.doc["textures"] = {{{"source", 0}}};
    expectLoadError(gltf.write(dir, "notexture"), "absent.png");
}

TEST(GltfBadInput, NodeCycle) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"children", {1}}});
    gltf.addNode({{"children", {0}}}, false);
    expectLoadError(gltf.write(dir, "cycle"), "must be a tree");
}

TEST(GltfBadInput, UnknownLightType) {
    TempDir dir;
    TestGltf gltf;
    gltf.addLight({{"type", "area"}});
    expectLoadError(gltf.write(dir, "area"), "type must be");
}

TEST(GltfBadInput, SpotOuterConeBeyondNinetyDegrees) {
    TempDir dir;
    TestGltf gltf;
    gltf.addLight({{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
    expectLoadError(gltf.write(dir, "cone"), "outerConeAngle must be in (0, pi/2]");
}

TEST(GltfBadInput, ImageInABufferViewPastItsBufferIsAnErrorNotAnOutOfBoundsRead) {
    // A fuzz finding: tinygltf hands the image decoder a pointer at the view's offset without a check.
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    gltf.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 1 << 20}, {"byteLength", 64}});
    gltf.doc["images"] = {{{"bufferView", gltf.doc["bufferViews"].size() - 1}, {"mimeType", "image/png"}}};
    expectLoadError(gltf.write(dir, "image_view"), "image 0: bufferView 2 ends at byte 1048640, past the end of its buffer");
}
