// The budgets of penumbra/scene_limits.h: each is refused with one line naming the budget and how to
// raise it, and the same scene loads once it is raised. The defaults load every real asset at hand.
#include <filesystem>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "error_message.h"
#include "gltf_test_files.h"
#include "penumbra/image.h"
#include "penumbra/scene_limits.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;
using penumbra::testing::writeFile;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

GltfLoadOptions withLimit(uint64_t SceneLimits::*field, uint64_t value) {
    GltfLoadOptions options;
    options.limits.*field = value;
    return options;
}

// The message loading `path` fails with; checks that it is one line naming the scene, the budget and
// how to raise it.
std::string budgetError(const std::string& path, const GltfLoadOptions& options, const std::string& budget) {
    const std::string message = penumbra::testing::errorMessage([&] { loadGltfScene(path, options); });
    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_FALSE(contains(message, "\n")) << message;
    EXPECT_TRUE(contains(message, "over the " + budget + " budget of ")) << message;
    EXPECT_TRUE(contains(message, "raise it with --limit " + budget + "=N")) << message;
    return message;
}

std::string triangleScene(const TempDir& dir, const std::string& name = "triangle") {
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    return gltf.write(dir, name);
}

// A triangle and `count` images of side x side pixels beside it (imageN.png).
std::string sceneWithImages(const TempDir& dir, int count, uint32_t side) {
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    for (int i = 0; i < count; ++i) {
        const std::string name = "image" + std::to_string(i) + ".png";
        writePng(Image(side, side, 4), dir.file(name));
        gltf.doc["images"].push_back({{"uri", name}});
    }
    return gltf.write(dir, "images");
}

uint32_t crc32(const std::string& bytes) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

std::string bigEndian(uint32_t value) {
    return {char(value >> 24), char(value >> 16), char(value >> 8), char(value)};
}

std::string pngChunk(const std::string& type, const std::string& data) {
    return bigEndian(uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
}

// A PNG of a valid header that claims width x height RGBA pixels, and no image data to speak of.
std::string pngHeaderClaiming(uint32_t width, uint32_t height) {
    const std::string ihdr = bigEndian(width) + bigEndian(height) + std::string("\x08\x06\x00\x00\x00", 5);
    return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", "") + pngChunk("IEND", "");
}

std::string littleEndian(uint32_t value) {
    return {char(value), char(value >> 8), char(value >> 16), char(value >> 24)};
}

// A .glb of the triangle scene with its binary chunk; `lengthFix` is added to the header's length.
std::string glbBytes(int64_t lengthFix, int64_t jsonLengthFix = 0) {
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    gltf.doc["buffers"] = {{{"byteLength", gltf.bin.size()}}};
    std::string json = gltf.doc.dump();
    while (json.size() % 4) json += ' ';
    std::string bin(gltf.bin.begin(), gltf.bin.end());
    while (bin.size() % 4) bin += '\0';
    const std::string chunks = littleEndian(uint32_t(int64_t(json.size()) + jsonLengthFix)) + "JSON" + json +
                               littleEndian(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
    return "glTF" + littleEndian(2) + littleEndian(uint32_t(int64_t(12 + chunks.size()) + lengthFix)) + chunks;
}

}  // namespace

TEST(SceneBudgets, SceneFileOverFileBytesIsRefused) {
    TempDir dir;
    const std::string path = triangleScene(dir);
    const std::string message = budgetError(path, withLimit(&SceneLimits::maxFileBytes, 100), "fileBytes");
    EXPECT_TRUE(contains(message, path + " is " + std::to_string(fs::file_size(path)) + " bytes")) << message;
}

TEST(SceneBudgets, SceneFileWithinARaisedFileBytesLoads) {
    TempDir dir;
    const std::string path = triangleScene(dir);
    EXPECT_NO_THROW(loadGltfScene(path, withLimit(&SceneLimits::maxFileBytes, fs::file_size(path))));
}

TEST(SceneBudgets, ReferencedFileOverFileBytesIsRefused) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    gltf.bin.resize(4096);  // a buffer larger than the scene file
    const std::string path = gltf.write(dir, "big_buffer");
    const std::string message = budgetError(path, withLimit(&SceneLimits::maxFileBytes, 4000), "fileBytes");
    EXPECT_TRUE(contains(message, "external file 'big_buffer.bin' is 4096 bytes")) << message;
}

namespace {

// A chain of `depth` nodes, the last holding the triangle.
std::string nodeChain(const TempDir& dir, int depth) {
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    for (int i = 0; i < depth; ++i) {
        nlohmann::json node = i + 1 < depth ? nlohmann::json{{"children", {i + 1}}} : nlohmann::json{{"mesh", mesh}};
        gltf.addNode(node, i == 0);
    }
    return gltf.write(dir, "chain");
}

std::string twoLights(const TempDir& dir) {
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    gltf.addLight({{"type", "point"}});
    gltf.addLight({{"type", "point"}});
    return gltf.write(dir, "lights");
}

// The triangle under a node whose extras nest `depth` arrays; the document, its node list, the node
// and its extras add 4 levels.
std::string nestedExtras(const TempDir& dir, int depth) {
    TestGltf gltf;
    nlohmann::json value = nlohmann::json::array();
    for (int i = 1; i < depth; ++i) value = nlohmann::json::array({value});
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}, {"extras", {{"deep", value}}}});
    return gltf.write(dir, "nested");
}

// One budget: a scene that needs exactly `needed` of it, and what the refusal says besides the budget.
struct BudgetCase {
    const char* name;
    uint64_t SceneLimits::*field;
    std::string (*scene)(const TempDir&);
    uint64_t needed;
    const char* detail;
};
void PrintTo(const BudgetCase& c, std::ostream* os) { *os << c.name; }


const BudgetCase kBudgetCases[] = {
    {"imageBytes", &SceneLimits::maxImageBytes, [](const TempDir& d) { return sceneWithImages(d, 1, 64); }, 64 * 64 * 4,
     "image 0 (64x64) decoded to RGBA8 is 16384"},
    {"textureBytes", &SceneLimits::maxTextureBytes, [](const TempDir& d) { return sceneWithImages(d, 2, 32); }, 2 * 32 * 32 * 4,
     "image 1 (32x32) brings the textureBytes to 8192"},
    {"vertices", &SceneLimits::maxVertices, [](const TempDir& d) { return triangleScene(d); }, 3,
     "mesh 0 primitive 0 brings the vertices to 3"},
    {"indices", &SceneLimits::maxIndices, [](const TempDir& d) { return triangleScene(d); }, 3,
     "mesh 0 primitive 0 brings the indices to 3"},
    {"nodes", &SceneLimits::maxNodes, [](const TempDir& d) { return nodeChain(d, 3); }, 3, "the node count is 3"},
    {"nodeDepth", &SceneLimits::maxNodeDepth, [](const TempDir& d) { return nodeChain(d, 3); }, 3, "node 2's depth is 3"},
    {"lights", &SceneLimits::maxLights, [](const TempDir& d) { return twoLights(d); }, 2, "the light count is 2"},
    {"jsonDepth", &SceneLimits::maxJsonDepth, [](const TempDir& d) { return nestedExtras(d, 20); }, 24,
     "the JSON nests more than 23 levels deep"},
};

class SceneBudget : public ::testing::TestWithParam<BudgetCase> {};

}  // namespace

TEST_P(SceneBudget, OneUnitShortIsRefusedNamingTheBudget) {
    TempDir dir;
    const BudgetCase& c = GetParam();
    const std::string message = budgetError(c.scene(dir), withLimit(c.field, c.needed - 1), c.name);
    EXPECT_TRUE(contains(message, c.detail)) << message;
}

TEST_P(SceneBudget, RaisedToWhatTheSceneNeedsLoads) {
    TempDir dir;
    const BudgetCase& c = GetParam();
    EXPECT_NO_THROW(loadGltfScene(c.scene(dir), withLimit(c.field, c.needed)));
}

INSTANTIATE_TEST_SUITE_P(EveryCountedBudget, SceneBudget, ::testing::ValuesIn(kBudgetCases),
                         [](const ::testing::TestParamInfo<BudgetCase>& info) { return std::string(info.param.name); });

TEST(SceneBudgets, PngHeaderClaimingSixtyThousandSquaredIsRefusedBeforeDecoding) {
    TempDir dir;
    TestGltf gltf;
    gltf.addNode({{"mesh", gltf.addTriangleMesh()}});
    writeFile(dir.file("huge.png"), pngHeaderClaiming(60000, 60000));
    gltf.doc["images"] = {{{"uri", "huge.png"}}};
    // From the header: 14.4 GB would be allocated were it decoded (the decoder's own 16384 limit
    // speaks only after the budget).
    const std::string message = budgetError(gltf.write(dir, "huge_image"), {}, "imageBytes");
    EXPECT_TRUE(contains(message, "image 0 (60000x60000) decoded to RGBA8 is 14400000000")) << message;
}

TEST(SceneBudgets, ASharedAccessorCountsOncePerUse) {
    TempDir dir;
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    gltf.doc["meshes"][mesh]["primitives"].push_back(gltf.doc["meshes"][mesh]["primitives"][0]);
    gltf.addNode({{"mesh", mesh}});
    budgetError(gltf.write(dir, "shared"), withLimit(&SceneLimits::maxVertices, 5), "vertices");
}

TEST(SceneBudgets, JsonNestedHundredsOfThousandsDeepIsRefusedNotAStackOverflow) {
    TempDir dir;
    const std::string path = dir.file("deep.gltf");
    writeFile(path, "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"extras\":" + std::string(200000, '[') +
                        std::string(200000, ']') + "}]}");
    budgetError(path, {}, "jsonDepth");
}

TEST(SceneBudgets, GlbHeaderClaimingMoreThanTheFileHoldsIsRefused) {
    TempDir dir;
    const std::string path = dir.file("long.glb");
    writeFile(path, glbBytes(+64));
    const std::string message = penumbra::testing::errorMessage([&] { loadGltfScene(path); });
    EXPECT_TRUE(contains(message, "the GLB header claims " + std::to_string(fs::file_size(path) + 64) + " bytes, the file holds "))
        << message;
}

TEST(SceneBudgets, GlbJsonChunkClaimingMoreThanTheHeaderGivesIsRefused) {
    TempDir dir;
    const std::string path = dir.file("long_json.glb");
    writeFile(path, glbBytes(0, 1 << 30));
    EXPECT_TRUE(contains(penumbra::testing::errorMessage([&] { loadGltfScene(path); }), "the GLB's JSON chunk claims"));
}

TEST(SceneBudgets, GlbHeaderClaimingMoreThanTheBudgetIsRefused) {
    TempDir dir;
    const std::string path = dir.file("huge.glb");
    writeFile(path, glbBytes(int64_t(3) << 30));  // a small file whose header claims 3 GiB
    const std::string message = budgetError(path, {}, "fileBytes");
    EXPECT_TRUE(contains(message, "the GLB header's length is 32212")) << message;
}

TEST(SceneBudgets, WellFormedGlbLoads) {
    const std::string bytes = glbBytes(0);
    EXPECT_EQ(loadGltfSceneFromMemory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "ok.glb").meshes.size(), 1u);
}

TEST(SceneBudgets, DefaultsLoadEveryRealAsset) {
    std::vector<fs::path> assets;
    const std::string testScenes = std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes";
    for (const std::string& folder : {std::string("/usr/share/assimp/models/glTF2"), testScenes}) {
        std::error_code error;
        for (auto it = fs::recursive_directory_iterator(folder, error); !error && it != fs::recursive_directory_iterator(); ++it)
            if (it->path().extension() == ".gltf" || it->path().extension() == ".glb") assets.push_back(it->path());
    }
    if (assets.empty()) GTEST_SKIP() << "no glTF assets installed";
    for (const fs::path& asset : assets) {
        // Some of assimp's models are broken on purpose (a test of its own importer) or need extensions
        // Penumbra lacks (Draco): those may fail, but never on a budget or the asset root.
        const std::string message = penumbra::testing::errorMessage([&] { loadGltfScene(asset.string()); });
        EXPECT_FALSE(contains(message, "budget")) << message;
        EXPECT_FALSE(contains(message, "asset root")) << message;
    }
}

TEST(SceneLimitOption, SetsTheNamedBudgetWithASuffix) {
    SceneLimits limits;
    setSceneLimit(limits, "fileBytes=64M");
    setSceneLimit(limits, "lights=16");
    EXPECT_EQ(limits.maxFileBytes, 64ull << 20);
    EXPECT_EQ(limits.maxLights, 16u);
}

TEST(SceneLimitOption, UnknownNameListsTheBudgets) {
    SceneLimits limits;
    EXPECT_TRUE(contains(penumbra::testing::errorMessage([&] { setSceneLimit(limits, "bytes=1"); }),
                         "unknown budget 'bytes' (the budgets are fileBytes, imageBytes, textureBytes"));
}

TEST(SceneLimitOption, ValueThatIsNotAWholeNumberIsRefused) {
    SceneLimits limits;
    for (const char* bad : {"fileBytes=", "fileBytes=-1", "fileBytes=1.5", "fileBytes=12T", "fileBytes=99999999999999999999"})
        EXPECT_TRUE(contains(penumbra::testing::errorMessage([&] { setSceneLimit(limits, bad); }), "must be a whole number"))
            << bad;
}

TEST(SceneLimitOption, AssignmentWithoutEqualsSignIsRefused) {
    SceneLimits limits;
    EXPECT_TRUE(contains(penumbra::testing::errorMessage([&] { setSceneLimit(limits, "fileBytes"); }),
                         "--limit expects NAME=VALUE"));
}

TEST(SceneLimitOption, EveryKeyNamesADistinctMember) {
    SceneLimits limits;
    for (const SceneLimitKey& key : sceneLimitKeys()) {
        limits.*key.field = 7;
        setSceneLimit(limits, std::string(key.name) + "=8");
        EXPECT_EQ(limits.*key.field, 8u) << key.name;
    }
    EXPECT_EQ(sceneLimitKeys().size(), sizeof(SceneLimits) / sizeof(uint64_t));
}
