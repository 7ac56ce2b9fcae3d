// A scene's external buffers and images stay inside its asset root (docs/security.md): each rule
// refuses its escape with one line naming the scene, the reference and the rule, and what the rules
// allow still loads. The fixture is made at test time: <tmp>/scene/scene.gltf with files beside it
// and under it, a FIFO, a folder and symlinks in it, and outside.bin / secret.png in <tmp>, outside it.
#include <sys/stat.h>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "error_message.h"
#include "gltf_test_files.h"
#include "penumbra/image.h"
#include "scene/asset_access.h"
#include "scene/gltf_loader.h"

namespace fs = std::filesystem;
using namespace penumbra;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;
using penumbra::testing::writeFile;

namespace {

void writeSmallPng(const fs::path& path) {
    Image image(2, 2, 4);
    image.pixels.assign(16, 200);
    writePng(image, path.string());
}

// <tmp>/scene/: beside.bin, beside.png, sub/inner.bin, folder.bin/, fifo.bin (a FIFO), inward -> sub,
// escape -> .., zero.bin -> /dev/zero; <tmp>: outside.bin, secret.png. Every .bin is the buffer of
// the one-triangle scene that write() puts in scene/scene.gltf.
class SceneFolder {
public:
    SceneFolder() {
        fs::create_directories(scene() / "sub");
        fs::create_directories(scene() / "folder.bin");
        gltf_.addNode({{"mesh", gltf_.addTriangleMesh()}});
        const std::string bin(gltf_.bin.begin(), gltf_.bin.end());
        for (const fs::path& path : {outside() / "outside.bin", scene() / "beside.bin", scene() / "sub" / "inner.bin"})
            writeFile(path.string(), bin);
        writeSmallPng(outside() / "secret.png");
        writeSmallPng(scene() / "beside.png");
        fs::create_directory_symlink("sub", scene() / "inward");
        fs::create_directory_symlink("..", scene() / "escape");
        fs::create_symlink("/dev/zero", scene() / "zero.bin");
        EXPECT_EQ(::mkfifo((scene() / "fifo.bin").c_str(), 0600), 0);
    }
    fs::path outside() const { return dir_.file(""); }
    fs::path scene() const { return dir_.file("scene"); }

    // scene/scene.gltf with its buffer read from `bufferUri` and, when `imageUri` is given, an image
    // read from it.
    std::string write(const std::string& bufferUri, const std::string& imageUri = "") const {
        nlohmann::json doc = gltf_.doc;
        doc["buffers"] = {{{"uri", bufferUri}, {"byteLength", gltf_.bin.size()}}};
        if (!imageUri.empty()) doc["images"] = {{{"uri", imageUri}}};
        const std::string path = (scene() / "scene.gltf").string();
        writeFile(path, doc.dump());
        return path;
    }

private:
    TempDir dir_;
    TestGltf gltf_;
};

// The message loading `path` fails with; checks it is one line that names the scene.
std::string loadError(const std::string& path, const GltfLoadOptions& options = {}) {
    const std::string message = penumbra::testing::errorMessage([&] { loadGltfScene(path, options); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<fs::path> gOpened;
void recordOpen(const fs::path& path) { gOpened.push_back(path); }

// A reference the rules refuse, and what the refusal says.
struct Refusal {
    const char* name;
    const char* bufferUri;
    const char* imageUri;
    const char* says;
};
void PrintTo(const Refusal& c, std::ostream* os) { *os << c.name; }


const Refusal kRefusals[] = {
    {"UpLevelBufferUri", "../outside.bin", "", "external file '../outside.bin' resolves to"},
    {"UpLevelImageUri", "beside.bin", "../secret.png", "external file '../secret.png' resolves to"},
    {"UpLevelToEtcPasswd", "../../../../../../../../etc/passwd", "", "resolves to /etc/passwd, outside the asset root"},
    {"PercentEncodedUpLevel", "..%2Foutside.bin", "", "external file '../outside.bin' resolves to"},
    {"PercentEncodedNulByte", "beside.bin%00.png", "", "holds a NUL byte"},
    {"FileUri", "file:///etc/passwd", "", "uses the URI scheme 'file:'"},
    {"HttpUri", "http://example.com/buffer.bin", "", "uses the URI scheme 'http:'"},
    {"SymlinkPointingOut", "escape/outside.bin", "", "'escape/outside.bin' resolves to"},
    {"SymlinkToADevice", "zero.bin", "", "'zero.bin' resolves to /dev/zero, outside the asset root"},
    {"Fifo", "fifo.bin", "", "'fifo.bin' is refused: not a regular file"},  // opening it would wait for a writer
    {"Folder", "folder.bin", "", "'folder.bin' is refused: it is a directory"},
    {"MissingFile", "missing.bin", "", "'missing.bin' does not exist"},
};

// References the rules allow.
struct Allowed {
    const char* name;
    const char* bufferUri;
    const char* imageUri;
};
void PrintTo(const Allowed& c, std::ostream* os) { *os << c.name; }


const Allowed kAllowed[] = {
    {"SiblingFile", "beside.bin", ""},
    {"SubfolderFile", "sub/inner.bin", ""},
    {"SymlinkPointingIn", "inward/inner.bin", ""},
    {"SymlinkOutAndBackIn", "escape/scene/beside.bin", ""},
    {"SiblingImage", "beside.bin", "beside.png"},
};

class AssetRootRefuses : public ::testing::TestWithParam<Refusal> {};
class AssetRootAllows : public ::testing::TestWithParam<Allowed> {};

template <typename Case>
std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    return info.param.name;
}

}  // namespace

TEST_P(AssetRootRefuses, InOneLineNamingTheReferenceAndTheRule) {
    SceneFolder folder;
    const std::string message = loadError(folder.write(GetParam().bufferUri, GetParam().imageUri));
    EXPECT_TRUE(contains(message, GetParam().says)) << message;
}

INSTANTIATE_TEST_SUITE_P(EveryRule, AssetRootRefuses, ::testing::ValuesIn(kRefusals), caseName<Refusal>);

TEST_P(AssetRootAllows, TheSceneLoads) {
    SceneFolder folder;
    EXPECT_EQ(loadGltfScene(folder.write(GetParam().bufferUri, GetParam().imageUri)).meshes.size(), 1u);
}

INSTANTIATE_TEST_SUITE_P(EveryAllowedReference, AssetRootAllows, ::testing::ValuesIn(kAllowed), caseName<Allowed>);

TEST(AssetRoot, AbsolutePathIsRefused) {
    SceneFolder folder;
    const std::string absolute = fs::canonical(folder.scene() / "beside.bin").string();  // inside the root, yet refused
    EXPECT_TRUE(contains(loadError(folder.write(absolute)), "'" + absolute + "' is an absolute path"));
}

TEST(AssetRoot, DeviceIsRefusedEvenInsideAWidenedRoot) {
    SceneFolder folder;
    GltfLoadOptions everything;
    everything.assetRoot = "/";
    EXPECT_TRUE(contains(loadError(folder.write("zero.bin"), everything),
                         "'zero.bin' is refused: not a regular file (a device, FIFO or socket)"));
}

TEST(AssetRoot, DataUriLoads) {
    SceneFolder folder;  // cube.gltf's buffer is a data: URI
    fs::copy_file(std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/cube.gltf", folder.scene() / "cube.gltf");
    EXPECT_FALSE(loadGltfScene((folder.scene() / "cube.gltf").string()).meshes.empty());
}

TEST(AssetRoot, WidenedAssetRootAllowsTheFolderAbove) {
    SceneFolder folder;
    GltfLoadOptions widened;
    widened.assetRoot = folder.outside().string();
    EXPECT_EQ(loadGltfScene(folder.write("../outside.bin"), widened).meshes.size(), 1u);
}

TEST(AssetRoot, WidenedAssetRootStillRefusesWhatLiesOutsideIt) {
    SceneFolder folder;
    GltfLoadOptions widened;
    widened.assetRoot = folder.outside().string();
    EXPECT_TRUE(contains(loadError(folder.write("../../../../../../../../etc/passwd"), widened), "outside the asset root"));
}

TEST(AssetRoot, MissingAssetRootIsAnError) {
    SceneFolder folder;
    GltfLoadOptions missing;
    missing.assetRoot = (folder.outside() / "nowhere").string();
    EXPECT_TRUE(contains(penumbra::testing::errorMessage([&] { loadGltfScene(folder.write("beside.bin"), missing); }),
                         "the asset root " + missing.assetRoot + " does not exist"));
}

TEST(AssetRoot, RefusedReferenceOpensNoFile) {
    SceneFolder folder;
    const std::string path = folder.write("../outside.bin");
    gOpened.clear();
    setFileOpenObserver(recordOpen);
    EXPECT_THROW(loadGltfScene(path), Error);
    setFileOpenObserver(nullptr);
    ASSERT_EQ(gOpened.size(), 1u);  // the scene file alone
    EXPECT_EQ(gOpened[0], fs::path(path));
}
