// `penumbra render` as a user runs it: the demo scene, a real glTF sample, and every kind of bad
// input ending in one line on stderr and a non-zero exit, never a crash.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "penumbra/image.h"

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

const std::string kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
const std::string kBoxTextured = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";

fs::path tempPath(const std::string& name) {
    // One folder per test process: ctest runs tests in parallel, and two tests writing one file (two
    // viewers watching the same reloaded.gltf) fail each other.
    const fs::path dir = fs::temp_directory_path() / ("penumbra_cli_render_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

}  // namespace

TEST(CliRender, DemoSceneRendersWithoutValidationMessages) {
    const fs::path out = tempPath("demo.png");
    const CliRun result = runPenumbra("render -o " + out.string() + " --width 320 --height 180 --device cpu --validation");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(result.err.find("validation"), std::string::npos) << result.err;
    const Image image = readPng(out.string());
    EXPECT_EQ(image.width, 320u);
    EXPECT_EQ(image.height, 180u);
    EXPECT_EQ(image.channels, 3u);
}

TEST(CliRender, RealGltfSampleRendersAndShowsGeometry) {
    const fs::path out = tempPath("engine.png");
    // The sample has no lights: the CLI adds a default sun and says so. Black behind it, so bright
    // pixels are the engine's (the default sky gradient is bright everywhere).
    const CliRun rendered = runPenumbra("render " + kEngine + " -o " + out.string() +
                                      " --width 160 --height 90 --device cpu --validation --set render.background=black");
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
    EXPECT_NE(rendered.err.find("added a default sun"), std::string::npos);
    const Image image = readPng(out.string());
    size_t lit = 0;
    for (uint8_t v : image.pixels) lit += v > 40;
    EXPECT_GT(lit, image.pixels.size() / 10) << "the engine should cover a good part of the frame";
}

// A scene seen from 900 m: the maxDistance rule warns, in one line that ends with its newline (so the
// next message starts a line of its own), and warns of nothing else.
TEST(CliRender, MaxDistanceWarningIsOneWholeLine) {
    std::ifstream cubeFile(std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/cube.gltf");
    nlohmann::json cube = nlohmann::json::parse(cubeFile);
    for (nlohmann::json& node : cube["nodes"])
        if (node.value("name", "") == "camera")
            for (int axis = 12; axis < 15; ++axis) node["matrix"][axis] = node["matrix"][axis].get<double>() * 100.0;
    const fs::path scene = tempPath("far_camera.gltf");
    std::ofstream(scene) << cube.dump();
    const CliRun result = runPenumbra("render " + scene.string() + " -o " + tempPath("far.png").string() +
                                      " --width 32 --height 24 --device cpu");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(result.err.rfind("penumbra: warning: shadows.maxDistance is not set", 0), 0u) << result.err;
    ASSERT_FALSE(result.err.empty());
    EXPECT_EQ(result.err.back(), '\n') << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST(CliRender, StatsReportDeviceTimingsAndShadowTiles) {
    const CliRun result = runPenumbra("render -o " + tempPath("s.png").string() +
                                    " --width 96 --height 64 --device cpu --stats -");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const nlohmann::json stats = nlohmann::json::parse(result.out);
    EXPECT_TRUE(stats["device"]["cpu"].get<bool>());
    EXPECT_TRUE(stats["gpuMs"].contains("main"));
    EXPECT_TRUE(stats["gpuMs"].contains("shadows.directional"));
    EXPECT_EQ(stats["shadows"]["directional"]["lightsReserved"].get<int>(), 1);
    EXPECT_EQ(stats["shadows"]["directional"]["tiles"].get<int>(), 4);
    EXPECT_TRUE(stats["gpuMs"].contains("lightClusters"));
    // The demo's two spot lights: each cluster holds at most both, and some hold one.
    EXPECT_GT(stats["lightsPerCluster"]["mean"].get<double>(), 0.0);
    EXPECT_LE(stats["lightsPerCluster"]["max"].get<int>(), 2);
    // The default shadow modes (auto) as a CPU device draws them.
    EXPECT_EQ(stats["directionalShadows"], "cascades");
    EXPECT_EQ(stats["spotShadows"], "atlas");
}

TEST(CliRender, MissingSceneFileIsOneLineError) {
    expectOneLineError(runPenumbra("render /nonexistent/scene.gltf -o " + tempPath("x.png").string()), "/nonexistent/scene.gltf");
}

TEST(CliRender, TruncatedGlbIsOneLineError) {
    const fs::path truncated = tempPath("truncated.glb");
    std::ifstream engine(kEngine, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(engine)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 3));
    expectOneLineError(runPenumbra("render " + truncated.string() + " -o " + tempPath("x.png").string()), "truncated.glb");
}

TEST(CliRender, UnwritableOutputIsOneLineErrorBeforeRendering) {
    expectOneLineError(runPenumbra("render -o /nonexistent/dir/out.png --device cpu"), "/nonexistent/dir/out.png");
}

TEST(CliRender, OutOfRangeSettingNamesTheKeyAndRange) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string() + " --set shadows.directional.cascadeCount=7"),
                       "shadows.directional.cascadeCount");
}

TEST(CliRender, UnknownSettingKeyIsOneLineError) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string() + " --set shadows.bogus=1"), "shadows.bogus");
}

TEST(CliRender, MissingSettingsFileIsOneLineError) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string() + " --settings /nonexistent.json"),
                       "/nonexistent.json");
}

TEST(CliRender, NoVulkanDeviceIsOneLineError) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string(), "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json"),
                       "no Vulkan device");
}

TEST(CliRender, DeviceIndexOutOfRangeIsOneLineError) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string() + " --device 99"), "--device 99");
}

TEST(CliRender, AovOfMissingLightIsOneLineError) {
    expectOneLineError(runPenumbra("render -o " + tempPath("x.png").string() + " --device cpu --aov shadow --light 42"),
                       "--light 42");
}

TEST(CliRender, TexturedSampleKeepsItsTexture) {
    const fs::path out = tempPath("box.png");
    const CliRun result = runPenumbra("render " + kBoxTextured + " -o " + out.string() + " --width 64 --height 64 --device cpu");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const Image image = readPng(out.string());
    // The Cesium logo texture is not one flat colour: many distinct values appear on the box.
    std::set<uint32_t> colours;
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
        colours.insert(uint32_t(image.pixels[p * 3]) << 16 | uint32_t(image.pixels[p * 3 + 1]) << 8 | image.pixels[p * 3 + 2]);
    EXPECT_GT(colours.size(), 50u);
}


TEST(CliRender, BuiltInFieldSceneRendersShadowsOfItsSpots) {
    const fs::path out = tempPath("field.png");
    const CliRun result = runPenumbra("render gen:field:4:2 --device cpu --validation --width 96 --height 54 --aov shadow "
                                      "--light 1 -o " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const Image aov = readPng(out.string(), 1);
    EXPECT_LT(*std::min_element(aov.pixels.begin(), aov.pixels.end()), 128);  // the spot's shadows are there
}

TEST(CliRender, MalformedBuiltInSceneIsOneLineError) {
    expectOneLineError(runPenumbra("render gen:field:zero --device cpu -o " + tempPath("bad.png").string()), "gen:field:zero");
}

TEST(CliExport, ExportedBuiltInSceneRendersLikeTheBuiltInScene) {
    const fs::path glb = tempPath("boxes.glb"), a = tempPath("boxes_a.png"), b = tempPath("boxes_b.png");
    ASSERT_EQ(runPenumbra("export gen:boxes:50 -o " + glb.string()).exitCode, 0);
    ASSERT_EQ(runPenumbra("render gen:boxes:50 --device cpu --width 64 --height 36 -o " + a.string()).exitCode, 0);
    ASSERT_EQ(runPenumbra("render " + glb.string() + " --device cpu --width 64 --height 36 -o " + b.string()).exitCode, 0);
    const CliRun diff = runPenumbra("diff " + a.string() + " " + b.string());
    ASSERT_EQ(diff.exitCode, 0) << diff.err;
    EXPECT_EQ(nlohmann::json::parse(diff.out)["pixelsOver1"], 0) << diff.out;
}

TEST(CliExport, UnknownExtensionIsOneLineError) {
    expectOneLineError(runPenumbra("export -o " + tempPath("scene.obj").string()), "scene.obj");
}
