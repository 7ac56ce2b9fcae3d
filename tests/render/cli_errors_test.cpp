// Every user error on the CLI is one line on stderr and exit code 1, and a command
// that fails writes no output file, not even an empty or half-written one: out of GPU
// memory and device loss are injected with PENUMBRA_FAULT_INJECTION. A scene that reaches outside
// its folder, or past a budget, is such an error in every command that loads one (docs/security.md).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "penumbra/image.h"

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

const std::string kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

// A fresh, empty folder for one test's files.
fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("penumbra_cli_errors_" + std::to_string(::getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

size_t fileCount(const fs::path& folder) {
    size_t count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++count;
    return count;
}

const std::string kSmall = " --width 64 --height 48 --device cpu";

// <tmp>/<name>/scene/cube.gltf: the canonical cube with one image, "../secret.png", which lies in
// <tmp>/<name>/, outside the scene's folder (docs/security.md). Returns the scene's path.
fs::path escapingScene(const std::string& name) {
    const fs::path root = freshFolder(name);
    fs::create_directories(root / "scene");
    std::ifstream in(std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/cube.gltf");
    nlohmann::json doc = nlohmann::json::parse(in);
    doc["images"] = {{{"uri", "../secret.png"}}};
    std::ofstream(root / "scene" / "cube.gltf") << doc.dump();
    Image secret(2, 2, 4);
    secret.pixels.assign(16, 255);
    writePng(secret, (root / "secret.png").string());
    return root / "scene" / "cube.gltf";
}

}  // namespace

TEST(CliErrors, ZeroWidthIsOneLine) { expectOneLineError(runPenumbra("render --width 0"), "--width"); }

TEST(CliErrors, SetWithoutAnEqualsSignNamesTheFlag) {
    expectOneLineError(runPenumbra("render --set shadows.maxDistance" + kSmall), "--set expects key=value");
}

TEST(CliErrors, UnknownDeviceKindNamesTheFlag) {
    expectOneLineError(runPenumbra("render --device fastest"), "--device fastest: device kind must be");
}

TEST(CliErrors, UnknownAovIsOneLine) { expectOneLineError(runPenumbra("render --aov foo"), "--aov"); }

TEST(CliErrors, UnknownOptionIsOneLine) { expectOneLineError(runPenumbra("render --bogus"), "--bogus"); }

TEST(CliErrors, MissingCommandIsOneLine) { expectOneLineError(runPenumbra(""), "subcommand"); }

TEST(CliErrors, NonNumericFrameCountIsOneLine) { expectOneLineError(runPenumbra("bench --frames many"), "--frames"); }

TEST(CliErrors, BenchMotionOutsideItsRangeIsOneLine) {
    expectOneLineError(runPenumbra("bench --move-objects 2" + kSmall), "--move-objects: 2 is not a number from 0 to 1");
    expectOneLineError(runPenumbra("bench --move-objects -0.5" + kSmall), "--move-objects");
    expectOneLineError(runPenumbra("bench --light-motion -1" + kSmall), "--light-motion: -1 is not a number from 0 to 180");
    expectOneLineError(runPenumbra("bench --light-motion 181" + kSmall), "--light-motion");
    expectOneLineError(runPenumbra("bench --light-motion nan" + kSmall), "--light-motion: nan");  // CLI::Range lets NaN in
}

TEST(CliErrors, PinCpuThatTheProcessMayNotUseIsOneLine) {
    expectOneLineError(runPenumbra("bench --pin-cpu 4095" + kSmall), "--pin-cpu 4095: this process may not run on that CPU");
    expectOneLineError(runPenumbra("bench --pin-cpu -1" + kSmall), "--pin-cpu");
}

TEST(CliErrors, DirectoryAsTheSceneIsOneLineSayingSo) {
    const fs::path dir = freshFolder("scene_dir");
    expectOneLineError(runPenumbra("render " + dir.string() + " -o " + (dir / "x.png").string()), "it is a directory");
}

TEST(CliErrors, DirectoryAsTheFieldModelIsOneLineSayingSo) {
    const fs::path dir = freshFolder("model_dir");
    expectOneLineError(runPenumbra("render gen:field:2 --model " + dir.string() + " -o " + (dir / "x.png").string()),
                       "it is a directory");
}

TEST(CliErrors, DirectoryAsTheSettingsIsOneLineSayingSo) {
    const fs::path dir = freshFolder("settings_dir");
    expectOneLineError(runPenumbra("render --settings " + dir.string() + " -o " + (dir / "x.png").string()),
                       "settings: " + dir.string() + ": cannot open file (it is a directory)");
}

TEST(CliErrors, DirectoryAsTheOutputIsOneLineAndStaysADirectory) {
    const fs::path dir = freshFolder("output_dir");
    fs::create_directories(dir / "out.png");
    expectOneLineError(runPenumbra("render -o " + (dir / "out.png").string() + kSmall), "it is a directory");
    EXPECT_TRUE(fs::is_directory(dir / "out.png"));
}

TEST(CliErrors, OutputInAMissingFolderCreatesNothing) {
    const fs::path dir = freshFolder("missing_folder");
    expectOneLineError(runPenumbra("render -o " + (dir / "no" / "out.png").string() + kSmall), "does not exist");
    EXPECT_EQ(fileCount(dir), 0u);
}

TEST(CliErrors, UnwritableStatsFileFailsBeforeTheImageIsWritten) {
    const fs::path dir = freshFolder("stats_dir");
    expectOneLineError(runPenumbra("render -o " + (dir / "out.png").string() + " --stats " + (dir / "no" / "s.json").string() +
                                   kSmall),
                       "s.json");
    EXPECT_EQ(fileCount(dir), 0u);
}

TEST(CliErrors, ReferenceChecksItsOutputBeforeTracing) {
    const fs::path dir = freshFolder("reference_out");
    expectOneLineError(runPenumbra("reference -o " + (dir / "no" / "r.png").string() + kSmall), "does not exist");
}

TEST(CliErrors, BenchChecksItsJsonPathBeforeRendering) {
    const fs::path dir = freshFolder("bench_json");
    expectOneLineError(runPenumbra("bench --frames 1 --json " + (dir / "no" / "b.json").string() + kSmall), "b.json");
}

TEST(CliErrors, DiffNamesTheFirstImageThatIsMissing) {
    const fs::path dir = freshFolder("diff_missing");
    expectOneLineError(runPenumbra("diff " + (dir / "a.png").string() + " " + (dir / "b.png").string()),
                       "cannot read " + (dir / "a.png").string() + ": cannot open file (it does not exist)");
}

TEST(CliErrors, DiffOfAFileThatIsNoPngSaysSo) {
    const fs::path dir = freshFolder("diff_text");
    std::ofstream(dir / "a.png") << "text";
    expectOneLineError(runPenumbra("diff " + (dir / "a.png").string() + " " + (dir / "a.png").string()), "not a PNG file");
}

TEST(CliErrors, SettingsThatAreNotJsonNameTheByte) {
    const fs::path dir = freshFolder("bad_json");
    std::ofstream(dir / "s.json") << "{\"shadows\": [1";
    expectOneLineError(runPenumbra("render --settings " + (dir / "s.json").string()), "is not valid JSON (byte");
}

TEST(CliErrors, SetValueWithALineBreakIsStillOneLine) {
    expectOneLineError(runPenumbra("render --set \"$(printf 'shadows.max\\nDistance=1')\""), "unknown key");
}

TEST(CliErrors, BadFaultInjectionIsOneLine) {
    expectOneLineError(runPenumbra("render" + kSmall, "PENUMBRA_FAULT_INJECTION=sometimes"), "PENUMBRA_FAULT_INJECTION");
}

TEST(CliErrors, OutOfGpuMemoryIsOneLineAndWritesNoImage) {
    const fs::path dir = freshFolder("oom");
    // The 8192 atlas of the first frame makes its own allocation: the one that fails at 3.
    const CliRun run = runPenumbra("render -o " + (dir / "out.png").string() +
                                       " --set shadows.directional.atlasSize=8192 --stats " + (dir / "s.json").string() +
                                       kSmall,
                                   "PENUMBRA_FAULT_INJECTION=allocation=3");
    expectOneLineError(run, "out of GPU memory");
    EXPECT_EQ(fileCount(dir), 0u);
}

TEST(CliErrors, SceneOverTheDeviceStorageRangeIsOneLine) {
    // 20001 instance records of 64 bytes on a device whose storage buffers seem to hold 1 MiB.
    expectOneLineError(runPenumbra("bench gen:boxes:20000 --frames 1" + kSmall,
                                   "PENUMBRA_FAULT_INJECTION=max-storage-buffer-range=1048576"),
                       "the scene does not fit on this GPU: its instances take 2 MiB, more than the device's largest "
                       "storage buffer (1 MiB)");
}

TEST(CliErrors, DeviceLostIsOneLineNamingThePassesAndLeavesTheOldImage) {
    const fs::path dir = freshFolder("lost");
    std::ofstream(dir / "out.png") << "the previous image";
    // Submission 1 uploads the scene, 2 reads back the tight fit's visible surfaces; 3 is the frame.
    const CliRun run = runPenumbra("render -o " + (dir / "out.png").string() + kSmall, "PENUMBRA_FAULT_INJECTION=submit=3");
    expectOneLineError(run, "GPU device lost (VK_ERROR_DEVICE_LOST) submitting frame 0 (passes shadows.culling, shadows.directional");
    std::ifstream old(dir / "out.png");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(old), {}), "the previous image");
    EXPECT_EQ(fileCount(dir), 1u);  // and no temporary beside it
}

TEST(CliErrors, DeviceLostWhileWaitingIsOneLine) {
    const fs::path dir = freshFolder("lost_wait");
    expectOneLineError(runPenumbra("render -o " + (dir / "out.png").string() + kSmall, "PENUMBRA_FAULT_INJECTION=wait=3"),
                       "while the GPU ran frame 0");
    EXPECT_EQ(fileCount(dir), 0u);
}

TEST(CliErrors, MillimetreModelGetsShadowsAndAWarningWithoutAMaxDistance) {
    if (!fs::exists(kEngine)) GTEST_SKIP() << "sample model not installed";
    const fs::path dir = freshFolder("engine");
    const CliRun run = runPenumbra("render " + kEngine + " --aov shadow -o " + (dir / "aov.png").string() + kSmall);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("shadows.maxDistance is not set and the scene lies"), std::string::npos) << run.err;
    const Image aov = readPng((dir / "aov.png").string());
    size_t shadowed = 0;
    for (uint8_t value : aov.pixels) shadowed += value < 128;
    EXPECT_GT(shadowed, 20u);  // at the default maxDistance of 100 (mm) there is none
}

TEST(CliErrors, RenderOfASceneReachingOutsideItsFolderIsOneLineAndWritesNothing) {
    const fs::path scene = escapingScene("render");
    const fs::path output = scene.parent_path() / "out.png";
    const CliRun run = runPenumbra("render " + scene.string() + " -o " + output.string() + kSmall);
    expectOneLineError(run, "external file '../secret.png' resolves to");
    EXPECT_NE(run.err.find("outside the asset root"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(output));
}

TEST(CliErrors, EveryCommandThatLoadsASceneRefusesOneReachingOutsideItsFolder) {
    const fs::path scene = escapingScene("commands");
    const std::string out = (scene.parent_path() / "out").string();
    for (const std::string& command :
         {"reference " + scene.string() + " -o " + out + ".png" + kSmall, "compare " + scene.string() + kSmall,
          "bench " + scene.string() + " --frames 1 --warmup 0" + kSmall, "export " + scene.string() + " -o " + out + ".gltf",
          "graph " + scene.string() + kSmall}) {
        SCOPED_TRACE(command);
        expectOneLineError(runPenumbra(command), "outside the asset root");
    }
}

TEST(CliRender, AssetRootWideningRendersTheScene) {
    const fs::path scene = escapingScene("widened");
    const fs::path output = scene.parent_path() / "out.png";
    const CliRun run = runPenumbra("render " + scene.string() + " --asset-root " + scene.parent_path().parent_path().string() +
                                   " -o " + output.string() + kSmall);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(fs::exists(output));
}

TEST(CliErrors, SceneOverABudgetNamesTheLimitThatRaisesIt) {
    const fs::path scene = escapingScene("budget");
    const CliRun run = runPenumbra("export " + scene.string() + " --asset-root " + scene.parent_path().parent_path().string() +
                                   " --limit imageBytes=15 -o " + (scene.parent_path() / "out.gltf").string());
    expectOneLineError(run, "over the imageBytes budget of 15 (raise it with --limit imageBytes=N");
}

TEST(CliErrors, UnknownLimitNameIsOneLine) {
    const fs::path dir = freshFolder("limit_name");
    expectOneLineError(runPenumbra("export --limit size=1 -o " + (dir / "x.gltf").string()), "--limit size=1: unknown budget 'size'");
}
