// penumbra-viewer as CI runs it: under Xvfb on lavapipe with the validation layers on (a message makes
// it exit 1), scripted with --screenshot, and the PNG measured: the window's size, the shadow view
// against penumbra render --aov shadow for the same camera and size, the atlas overlay.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "penumbra/image.h"
#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "viewer_test_support.h"

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

Image renderedShadowAov(const std::string& scene, uint32_t light, uint32_t width, uint32_t height) {
    const fs::path out = tempPath("aov_" + std::to_string(light) + ".png");
    const CliRun run = runPenumbra("render " + scene + " --device cpu --aov shadow --light " + std::to_string(light) +
                                   " --width " + std::to_string(width) + " --height " + std::to_string(height) + " -o " +
                                   out.string());
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return readPng(out.string());
}

// Fraction of pixels whose lit / shadowed class (at 0.5) differs: the viewer's red channel (its
// shadow view is gray) against a 1-channel AOV.
double classDifference(const Image& viewer, const Image& aov) {
    size_t differ = 0;
    for (size_t p = 0; p < aov.pixels.size(); ++p) differ += (viewer.pixels[p * 3] >= 128) != (aov.pixels[p] >= 128);
    return double(differ) / double(aov.pixels.size());
}

double shadowedFraction(const Image& aov) {
    size_t shadowed = 0;
    for (uint8_t v : aov.pixels) shadowed += v < 128;
    return double(shadowed) / double(aov.pixels.size());
}

}  // namespace

TEST(Viewer, ScreenshotHasTheWindowsSize) {
    SKIP_WITHOUT_XVFB();
    const Image image = viewerScreenshot(kScenes + "cube.gltf", "size.png", "", 336, 200, 2);
    EXPECT_EQ(image.width, 336u);
    EXPECT_EQ(image.height, 200u);
    EXPECT_EQ(image.channels, 3u);
}

TEST(Viewer, ShadowViewIsTheShadowAovOfPenumbraRender) {
    SKIP_WITHOUT_XVFB();
    struct Case {
        const char* scene;
        uint32_t light;
    };
    for (const Case& c : {Case{"cube.gltf", 0}, Case{"spot_lights.gltf", 1}}) {
        const std::string scene = kScenes + c.scene;
        const Image viewer = viewerScreenshot(scene, "shadow.png", "--view shadow --light " + std::to_string(c.light));
        const Image aov = renderedShadowAov(scene, c.light, 320, 180);
        ASSERT_EQ(viewer.width, aov.width) << c.scene;
        ASSERT_EQ(viewer.height, aov.height) << c.scene;
        EXPECT_GT(shadowedFraction(aov), 0.01) << c.scene << ": the comparison needs shadow in view";
        const double difference = classDifference(viewer, aov);
        std::printf("%s light %u: shadow class differs in %.4f %% of pixels\n", c.scene, c.light, 100.0 * difference);
        EXPECT_LT(difference, 0.001) << c.scene;
    }
}

TEST(Viewer, AtlasViewOverlaysTheShadowAtlasBottomLeft) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    const Image final = viewerScreenshot(scene, "final.png", "--view final");
    const Image atlas = viewerScreenshot(scene, "atlas.png", "--view atlas");
    ASSERT_EQ(final.pixels.size(), atlas.pixels.size());
    // Pixels that differ: the overlay (at most 45 % of the window's height, 8 px from the bottom-left
    // corner; a square here, the scene has only the directional atlas) against the top-right quadrant,
    // where only shadow-edge pixels may differ (the atlas view also renders one-shot frames, whose tight
    // fit reduces their own depth).
    size_t inside = 0, insideCount = 0, topRight = 0, topRightCount = 0;
    const uint32_t side = uint32_t(0.4f * float(final.height));
    for (uint32_t y = 0; y < final.height; ++y)
        for (uint32_t x = 0; x < final.width; ++x) {
            const size_t p = (size_t(y) * final.width + x) * 3;
            const bool differs = final.pixels[p] != atlas.pixels[p] || final.pixels[p + 1] != atlas.pixels[p + 1] ||
                                 final.pixels[p + 2] != atlas.pixels[p + 2];
            if (x >= 10 && x < side && y >= final.height - side && y < final.height - 10) {
                inside += differs;
                ++insideCount;
            }
            if (x >= final.width / 2 && y < final.height / 2) {
                topRight += differs;
                ++topRightCount;
            }
        }
    EXPECT_GT(double(inside) / double(insideCount), 0.8) << "the atlas overlay is missing";
    EXPECT_LT(double(topRight) / double(topRightCount), 0.01) << "the atlas view changed the scene outside the overlay";
}

TEST(Viewer, PanelsDrawOverTheViewWithoutValidationMessages) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "spot_lights.gltf";
    const Image plain = viewerScreenshot(scene, "plain.png", "", 640, 360, 4);
    const Image panels = viewerScreenshot(scene, "panels.png", "--panels", 640, 360, 4);
    ASSERT_EQ(plain.pixels.size(), panels.pixels.size());
    // The inspector opens at the top left (8, 8), the stats panel at the top right.
    size_t differ = 0, count = 0;
    for (uint32_t y = 20; y < 120; ++y)
        for (uint32_t x = 20; x < 200; ++x, ++count) {
            const size_t p = (size_t(y) * plain.width + x) * 3;
            differ += plain.pixels[p] != panels.pixels[p] || plain.pixels[p + 2] != panels.pixels[p + 2];
        }
    EXPECT_GT(double(differ) / double(count), 0.5) << "no inspector panel at the top left";
}

TEST(Viewer, MissingFileIsOneLineError) {
    if (!kViewer) GTEST_SKIP() << "penumbra-viewer is not built";
    const std::vector<std::string> missingFiles = {"/nonexistent/scene.gltf", "--compare-settings /nonexistent/settings.json"};
    for (const std::string& missing : missingFiles) {
        const CliRun run = runProgram(kViewer, missing + " --screenshot " + tempPath("x.png").string());
        EXPECT_EQ(run.exitCode, 1) << missing;
        EXPECT_EQ(run.err.rfind("penumbra-viewer: ", 0), 0u) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
        EXPECT_NE(run.err.find(missing.substr(missing.find('/'))), std::string::npos) << run.err;
    }
}

TEST(Viewer, BadOptionIsOneLineError) {
    if (!kViewer) GTEST_SKIP() << "penumbra-viewer is not built";
    for (const char* arguments : {"--view sideways", "--frames 0", "--set shadows.directional.cascadeCount=9"}) {
        const CliRun run = runProgram(kViewer, arguments);
        EXPECT_EQ(run.exitCode, 1) << arguments;
        EXPECT_EQ(run.err.rfind("penumbra-viewer: ", 0), 0u) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    }
}

TEST(Viewer, CameraPathPlaysByFrameIndexAndEndsOnItsLastKeyframe) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    // Sphere-fitted cascades depend on this frame's camera only (the tight fit reads the previous
    // frame's depth), so a frame's image is a function of its camera.
    const std::string fit = " --set shadows.directional.fit=sphere";
    // Record the scene's camera: recording starts with the first frame, the file is written at exit.
    const fs::path recorded = tempPath("recorded.json");
    fs::remove(recorded);
    viewerScreenshot(scene, "recording.png", "--record-camera-path " + recorded.string() + fit, 320, 180, 2);
    ASSERT_TRUE(fs::exists(recorded));
    const nlohmann::json path = nlohmann::json::parse(std::ifstream(recorded));
    ASSERT_EQ(path["keyframes"].size(), 2u);
    const nlohmann::json start = path["keyframes"][0];
    EXPECT_NEAR(start["position"][0].get<float>(), 4.0f, 1e-4f);  // cube.gltf's camera node
    EXPECT_NEAR(start["position"][1].get<float>(), 4.5f, 1e-4f);
    EXPECT_NEAR(start["position"][2].get<float>(), 7.0f, 1e-4f);

    nlohmann::json moved = start;
    moved["position"] = {2.0f, 5.0f, 5.5f};
    auto pathOf = [&](const nlohmann::json& a, const nlohmann::json& b) {
        nlohmann::json first = a, second = b;
        first["time"] = 0.0;
        second["time"] = 1.5;
        return nlohmann::json{{"keyframes", {first, second}}}.dump();
    };
    const fs::path toScene = writeText("to_scene.json", pathOf(moved, start));
    const fs::path toMoved = writeText("to_moved.json", pathOf(start, moved));
    const fs::path still = writeText("still.json", nlohmann::json{{"keyframes", {start}}}.dump());
    auto play = [&](const fs::path& file, const std::string& name) {
        return viewerScreenshot(scene, name, "--camera-path " + file.string() + fit, 320, 180, 4);
    };
    const Image arrived = play(toScene, "arrived.png");
    const Image again = play(toScene, "again.png");
    const Image stayed = play(still, "stayed.png");
    const Image left = play(toMoved, "left.png");
    ASSERT_FALSE(arrived.empty());
    ASSERT_EQ(arrived.pixels.size(), stayed.pixels.size());
    ASSERT_EQ(arrived.pixels.size(), left.pixels.size());
    EXPECT_EQ(differingFraction(arrived, again), 0.0) << "the same path gives the same screenshot";
    EXPECT_EQ(differingFraction(arrived, stayed), 0.0) << "the screenshot is the path's last keyframe";
    EXPECT_GT(differingFraction(arrived, left), 0.1) << "a path that ends elsewhere shows something else";
}

TEST(Viewer, BadCameraPathIsOneLineError) {
    if (!kViewer) GTEST_SKIP() << "penumbra-viewer is not built";
    const fs::path notJson = writeText("not_json.json", "{\"keyframes\": [");
    const fs::path noKeyframes = writeText("empty_path.json", "{\"keyframes\": []}");
    const fs::path badRotation =
        writeText("bad_rotation.json", R"({"keyframes": [{"time": 0, "position": [0, 1, 2], "rotation": [0, 0, 1]}]})");
    for (const fs::path& file : {notJson, noKeyframes, badRotation, tempPath("missing_path.json")}) {
        const CliRun run = runProgram(kViewer, "--camera-path " + file.string() + " --screenshot " + tempPath("x.png").string());
        EXPECT_EQ(run.exitCode, 1) << file;
        EXPECT_EQ(run.err.rfind("penumbra-viewer: camera path " + file.string(), 0), 0u) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    }
}

namespace {

// Frames of a reload run. The test writes the file when it reads the viewer's "opened" line, and the
// viewer reloads two polls (frames) after it sees the change; a loaded CI machine (2 cores, two tests
// at once) may wake the test late, while a 240x135 frame takes 15-40 ms, so the run lasts about a
// second past the write. (CI failed once, 2026-12-02, when this test and the bad-file one ran at once
// on the same reloaded.gltf: tempPath is now one folder per test process.)
constexpr uint32_t kReloadFrames = 30;
// Frames of the runs the reloaded image is compared with: these images depend on the camera and the
// scene only (kRepeatable), not on how many frames came before.
constexpr uint32_t kComparedFrames = 4;

// cube.gltf with the ground's base colour set to blue; `wsCameraMove` added to the camera's position.
std::string editedCubeScene(const glm::vec3& wsCameraMove) {
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(kScenes + "cube.gltf"));
    gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.1, 0.2, 0.9, 1.0};
    for (nlohmann::json& node : gltf["nodes"])
        if (node.value("name", "") == "camera")
            for (int i = 0; i < 3; ++i) node["matrix"][12 + i] = node["matrix"][12 + i].get<float>() + wsCameraMove[i];
    return gltf.dump();
}

// Runs the viewer on a copy of cube.gltf and, as soon as it says it opened it, writes `replacement`
// over the copy; --watch-poll-ms 0 checks the file every frame, so the reload comes a few frames later
// (the viewer waits until the file's stamp held for two checks), long before the last frame.
CliRun reloadRun(const std::string& replacement, const fs::path& out, const std::string& options) {
    const fs::path scene = tempPath("reloaded.gltf");
    fs::copy_file(kScenes + "cube.gltf", scene, fs::copy_options::overwrite_existing);
    fs::remove(out);
    bool written = false;
    const CliRun run = runViewerFollowingStdout(
        scriptedArguments(scene.string(), out, "--watch-poll-ms 0 " + options, 240, 135, kReloadFrames), [&](const std::string& line) {
            if (written || line.find("opened " + scene.string()) == std::string::npos) return;
            std::ofstream(scene) << replacement;
            written = true;
        });
    EXPECT_TRUE(written) << run.out;
    return run;
}

}  // namespace

TEST(Viewer, ReloadsTheSceneFileWhenItChangesAndKeepsCameraAndSettings) {
    SKIP_WITHOUT_XVFB();
    // The new file moves its camera: the viewer keeps the user's, so the image must be the new scene seen
    // from the old camera, with the settings given at the start (aces tone mapping).
    const fs::path out = tempPath("reloaded.png");
    const CliRun run = reloadRun(editedCubeScene(glm::vec3(-3.0f, 2.0f, 1.0f)), out, kRepeatable);
    const Image reloaded = screenshotOf(run, out);
    EXPECT_NE(run.out.find("penumbra-viewer: reloaded "), std::string::npos) << run.out;
    const fs::path expectedScene = writeText("expected.gltf", editedCubeScene(glm::vec3(0.0f)));
    const Image expected = viewerScreenshot(expectedScene.string(), "expected.png", kRepeatable, 240, 135, kComparedFrames);
    ASSERT_FALSE(reloaded.empty());
    ASSERT_EQ(reloaded.pixels.size(), expected.pixels.size());
    size_t blue = 0;  // cube.gltf's ground is gray
    for (size_t p = 0; p < reloaded.pixels.size(); p += 3) blue += reloaded.pixels[p + 2] > reloaded.pixels[p] + 40;
    EXPECT_GT(double(blue) / double(reloaded.pixels.size() / 3), 0.2) << "the blue ground of the changed file is not shown";
    EXPECT_LT(differingFraction(reloaded, expected), 0.001) << "the reload did not keep the camera or the settings";
}

TEST(Viewer, BadFileOnReloadKeepsTheOldSceneAndShowsTheError) {
    SKIP_WITHOUT_XVFB();
    nlohmann::json bad = nlohmann::json::parse(std::ifstream(kScenes + "cube.gltf"));
    bad["materials"][0]["extras"]["shadows"] = "sometimes";
    const fs::path out = tempPath("bad_reload.png");
    const CliRun run = reloadRun(bad.dump(), out, kRepeatable);
    const Image kept = screenshotOf(run, out);
    const Image old = viewerScreenshot(kScenes + "cube.gltf", "old.png", kRepeatable, 240, 135, kComparedFrames);
    ASSERT_FALSE(kept.empty());
    ASSERT_EQ(kept.pixels.size(), old.pixels.size());
    // One line on stderr, the loader's message.
    EXPECT_EQ(run.err.rfind("penumbra-viewer: ", 0), 0u) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_NE(run.err.find("sometimes"), std::string::npos) << run.err;
    // The old scene above the error line; the line's red text at the bottom (24 px) of the window.
    const uint32_t lineTop = kept.height - 24;
    size_t differ = 0, red = 0, redBefore = 0;
    for (uint32_t y = 0; y < kept.height; ++y)
        for (uint32_t x = 0; x < kept.width; ++x) {
            const size_t p = (size_t(y) * kept.width + x) * 3;
            auto isRed = [&](const Image& i) {  // the text's red, sRGB-encoded by the swapchain
                return i.pixels[p] > 180 && i.pixels[p] > i.pixels[p + 1] + 60 && i.pixels[p] > i.pixels[p + 2] + 60;
            };
            const bool same = kept.pixels[p] == old.pixels[p] && kept.pixels[p + 1] == old.pixels[p + 1] &&
                              kept.pixels[p + 2] == old.pixels[p + 2];
            if (y < lineTop) differ += !same;
            else red += isRed(kept), redBefore += isRed(old);
        }
    EXPECT_EQ(differ, 0u) << "the old scene was not kept";
    EXPECT_GT(red, 40u) << "no error line over the view";
    EXPECT_EQ(redBefore, 0u) << "the measure of the error line sees red in the scene itself";
}

namespace {

// Pixels of each cascade's line colour (red, green, blue, yellow: src/viewer/panels.cpp's
// cascadeLineColor), which nothing in cube.gltf on a black background has.
std::array<size_t, 4> cascadeLinePixels(const Image& image) {
    std::array<size_t, 4> counts{};
    for (size_t p = 0; p < image.pixels.size(); p += 3) {
        const int r = image.pixels[p], g = image.pixels[p + 1], b = image.pixels[p + 2];
        counts[0] += r > 200 && g < 60 && b < 60;
        counts[1] += g > 200 && r < 60 && b < 60;
        counts[2] += b > 200 && r < 60 && g < 140;
        counts[3] += r > 200 && g > 200 && b < 60;
    }
    return counts;
}

}  // namespace

TEST(Viewer, FrustaViewDrawsTheLinesOfEachCascade) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf", black = "--set render.background=black ";
    auto linePixels = [&](const std::string& name, const std::string& options) {
        const Image image = viewerScreenshot(scene, name, black + options, 240, 135, 3);
        EXPECT_FALSE(image.empty()) << options;
        return cascadeLinePixels(image);
    };
    const std::array<size_t, 4> four = linePixels("frusta4.png", "--view frusta");
    const std::array<size_t, 4> two = linePixels("frusta2.png", "--view frusta --set shadows.directional.cascadeCount=2");
    const std::array<size_t, 4> final = linePixels("final_lines.png", "--view final");
    std::printf("line pixels per cascade: four cascades %zu %zu %zu %zu, two %zu %zu\n", four[0], four[1], four[2], four[3],
                two[0], two[1]);
    for (size_t c = 0; c < 4; ++c) {
        EXPECT_GT(four[c], 5u) << "cascade " << c << ": no lines of its colour in the frusta view";
        EXPECT_EQ(final[c], 0u) << "cascade " << c << ": its colour is in the final view, which draws no lines";
    }
    EXPECT_GT(two[0], 5u);
    EXPECT_GT(two[1], 5u);
    EXPECT_EQ(two[2], 0u) << "two cascades, yet a third one's lines";
    EXPECT_EQ(two[3], 0u) << "two cascades, yet a fourth one's lines";
}

namespace {

// Pixels of exactly one colour of penumbra compare --diff's picture (red: false shadow, cyan: false lit).
size_t pixelsOf(const Image& image, uint8_t r, uint8_t g, uint8_t b) {
    size_t n = 0;
    for (size_t p = 0; p + 2 < image.pixels.size(); p += 3)
        n += image.pixels[p] == r && image.pixels[p + 1] == g && image.pixels[p + 2] == b;
    return n;
}

}  // namespace

TEST(Viewer, ReferenceViewIsPenumbraComparesPicture) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    // Sphere fit and the hardware raster: the viewer's shadow AOV after a few frames is penumbra
    // compare's first frame. At 160x90 cube.gltf has a few false lit pixels (cyan) along the cube's
    // shadow and no false shadow (red); tests/unit/reference_view_test.cpp has both colours.
    const std::string settings = "--set shadows.directional.fit=sphere --set shadows.raster=hw";
    const Image viewer = viewerScreenshot(scene, "reference.png", "--view reference " + settings, 160, 90, 2);
    const fs::path diffPath = tempPath("compare_diff.png");
    const CliRun run =
        runPenumbra("compare " + scene + " --device cpu --width 160 --height 90 --json --diff " + diffPath.string() + " " + settings);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json metrics = nlohmann::json::parse(run.out);
    const Image compare = readPng(diffPath.string());
    ASSERT_EQ(viewer.pixels.size(), compare.pixels.size());
    const double differing = differingFraction(viewer, compare);
    const size_t red = pixelsOf(viewer, 255, 0, 0), cyan = pixelsOf(viewer, 0, 255, 255);
    std::printf("%.3f %% of pixels differ from penumbra compare --diff; red %zu (compare %zu), cyan %zu (compare %zu)\n",
                100.0 * differing, red, pixelsOf(compare, 255, 0, 0), cyan, pixelsOf(compare, 0, 255, 255));
    EXPECT_LT(differing, 0.005);
    ASSERT_EQ(pixelsOf(compare, 255, 0, 0), metrics["falseShadow"].get<size_t>()) << "the measure misreads compare's picture";
    ASSERT_EQ(pixelsOf(compare, 0, 255, 255), metrics["falseLit"].get<size_t>()) << "the measure misreads compare's picture";
    ASSERT_EQ(metrics["falseShadow"].get<size_t>(), 0u) << "the scene no longer has the expected disagreements";
    ASSERT_GT(metrics["falseLit"].get<size_t>(), 0u) << "the scene no longer has the expected disagreements";
    EXPECT_EQ(red, 0u) << "false shadow (red) where penumbra compare has none";
    EXPECT_NEAR(double(cyan), double(metrics["falseLit"].get<size_t>()), 2.0) << "false lit (cyan) as penumbra compare counts it";
}

TEST(Viewer, ReferenceViewOfABadLightIsOneLineError) {
    if (!kViewer) GTEST_SKIP() << "penumbra-viewer is not built";
    // Past the end: refused before any window opens.
    const CliRun past = runProgram(kViewer, kScenes + "cube.gltf --view reference --light 3 --screenshot " + tempPath("x.png").string());
    EXPECT_EQ(past.exitCode, 1);
    EXPECT_EQ(past.err, "penumbra-viewer: --light 3: the scene has 1 lights\n");
    if (!canRunViewer()) return;
    // A light without shadows: the tracer's message, from the scripted run's trace.
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(kScenes + "cube.gltf"));
    gltf["extensions"]["KHR_lights_punctual"]["lights"][0]["extras"]["shadows"] = "none";
    const fs::path scene = writeText("no_shadows.gltf", gltf.dump());
    const fs::path out = tempPath("no_shadows.png");
    fs::remove(out);
    const CliRun none = runProgram(kViewer, scriptedArguments(scene.string(), out, "--view reference", 64, 36, 1), xvfbRun());
    EXPECT_EQ(none.exitCode, 1);
    EXPECT_EQ(none.err.rfind("penumbra-viewer: reference view: ", 0), 0u) << none.err;
    EXPECT_EQ(none.err.find('\n'), none.err.size() - 1) << none.err;
    EXPECT_NE(none.err.find("light 0"), std::string::npos) << none.err;
    EXPECT_FALSE(fs::exists(out));
}

namespace {

// Pixels that differ between two RGB images of one size, over columns [x0, x1).
double differingFractionInColumns(const Image& a, const Image& b, uint32_t x0, uint32_t x1) {
    size_t differ = 0, count = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = x0; x < x1; ++x, ++count) {
            const size_t p = (size_t(y) * a.width + x) * 3;
            differ += a.pixels[p] != b.pixels[p] || a.pixels[p + 1] != b.pixels[p + 1] || a.pixels[p + 2] != b.pixels[p + 2];
        }
    return double(differ) / double(count);
}

Image renderedWithSettings(const std::string& scene, const fs::path& settings, const std::string& name) {
    const fs::path out = tempPath(name);
    const CliRun run = runPenumbra("render " + scene + " --device cpu --width 160 --height 90 --settings " + settings.string() +
                                   " -o " + out.string());
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return readPng(out.string());
}

}  // namespace

TEST(Viewer, CompareSettingsSplitsTheWindowBetweenTwoSettings) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    // Both repeatable (sphere fit, hardware raster); the second with one cascade and ACES tone mapping.
    const fs::path current = writeText("split_current.json", R"({"shadows": {"raster": "hw", "directional": {"fit": "sphere"}}})");
    const fs::path second = writeText("split_second.json", R"({"shadows": {"raster": "hw", "directional": {"fit": "sphere",
        "cascadeCount": 1}}, "render": {"toneMapping": "aces"}})");
    const Image split = viewerScreenshot(scene, "split.png", "--settings " + current.string() + " --compare-settings " + second.string(),
                                         160, 90, 2);
    const Image left = renderedWithSettings(scene, current, "split_left.png");
    const Image right = renderedWithSettings(scene, second, "split_right.png");
    ASSERT_EQ(split.pixels.size(), left.pixels.size());
    ASSERT_EQ(split.pixels.size(), right.pixels.size());
    const double leftDiffers = differingFractionInColumns(split, left, 0, 80);
    const double rightDiffers = differingFractionInColumns(split, right, 80, 160);
    std::printf("left half vs penumbra render --settings current: %.3f %% differ; right half vs --settings second: %.3f %%\n",
                100.0 * leftDiffers, 100.0 * rightDiffers);
    ASSERT_GT(differingFractionInColumns(left, right, 0, 160), 0.3) << "the two settings must give different images";
    EXPECT_LT(leftDiffers, 0.002) << "the left half is not the current settings' image";
    EXPECT_LT(rightDiffers, 0.002) << "the right half is not the second settings' image";
}

namespace {

// penumbra render's colour image or --aov cascades of `scene` at width x height with `options`.
Image rendered(const std::string& scene, const std::string& name, const std::string& options, uint32_t width,
               uint32_t height) {
    const fs::path out = tempPath(name);
    const CliRun run = runPenumbra("render " + scene + " --device cpu --width " + std::to_string(width) + " --height " +
                                   std::to_string(height) + " " + options + " -o " + out.string());
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return run.exitCode == 0 ? readPng(out.string()) : Image{};
}

// The cascade of a cascades-view pixel (none black, then red, green, blue, yellow), -1 for none.
int cascadeOf(const Image& image, size_t pixel) { return test::aovCascadeIndexOf(image, pixel, 4); }

}  // namespace

TEST(Viewer, CascadesViewIsTheCascadesAovOfPenumbraRender) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    // Sphere-fitted cascades: the tight fit reads the previous frame's depth, which moves the viewer's
    // fifth frame's cascade borders by a pixel row from penumbra render's first (2.7 % of the pixels).
    // Manual splits of 30 m put three cascades in view.
    const std::string sphere = " --set shadows.directional.fit=sphere --set shadows.directional.cascadeSplits=manual"
                               " --set shadows.maxDistance=30";
    const Image viewer = viewerScreenshot(scene, "cascades.png", "--view cascades" + sphere);
    const Image aov = rendered(scene, "cascades_aov.png", "--aov cascades" + sphere, 320, 180);
    ASSERT_EQ(viewer.width, aov.width);
    ASSERT_EQ(viewer.height, aov.height);
    ASSERT_EQ(viewer.channels, aov.channels);
    // Tolerance: the cascade differs in fewer than 0.1 % of the pixels (the shadow view's).
    size_t differ = 0, pixels = size_t(aov.width) * aov.height;
    std::array<size_t, 5> used{};
    for (size_t p = 0; p < pixels; ++p) {
        differ += cascadeOf(viewer, p) != cascadeOf(aov, p);
        ++used[size_t(cascadeOf(aov, p) + 1)];
    }
    std::printf("cascade differs in %.4f %% of pixels; pixels per cascade (none, 0..3): %zu %zu %zu %zu %zu\n",
                100.0 * double(differ) / double(pixels), used[0], used[1], used[2], used[3], used[4]);
    EXPECT_GE(std::count_if(used.begin() + 1, used.end(), [&](size_t n) { return n > pixels / 100; }), 3)
        << "the comparison needs three cascades in view";
    EXPECT_LT(double(differ) / double(pixels), 0.001);
}

TEST(Viewer, MailboxPresentsTheSameImageAsFifo) {
    SKIP_WITHOUT_XVFB();
    const std::string scene = kScenes + "cube.gltf";
    const fs::path fifoPath = tempPath("fifo.png"), mailboxPath = tempPath("mailbox.png");
    auto run = [&](const std::string& mode, const fs::path& out) {
        return runProgram(kViewer, scriptedArguments(scene, out, "--present " + mode + " " + kRepeatable, 240, 135, 3), xvfbRun());
    };
    const CliRun fifoRun = run("fifo", fifoPath), mailboxRun = run("mailbox", mailboxPath);
    const Image fifo = screenshotOf(fifoRun, fifoPath), mailbox = screenshotOf(mailboxRun, mailboxPath);
    ASSERT_FALSE(fifo.empty());
    ASSERT_EQ(fifo.pixels.size(), mailbox.pixels.size());
    EXPECT_EQ(differingFraction(fifo, mailbox), 0.0);
    // Lavapipe's Xvfb surface offers mailbox: no fallback, no warning.
    EXPECT_EQ(mailboxRun.err, "");
    EXPECT_EQ(fifoRun.err, "");
}

namespace {

// The viewer's final view of `scene` with `options` at 240 x 135 against penumbra render's image with
// the same options: the same pixels but for fewer than 0.1 %.
void expectViewerShowsPenumbraRendersImage(const std::string& scene, const std::string& name, const std::string& options) {
    const Image viewer = viewerScreenshot(scene, name + ".png", options, 240, 135, 3);
    const Image render = rendered(scene, name + "_render.png", options, 240, 135);
    ASSERT_FALSE(viewer.empty());
    ASSERT_EQ(viewer.width, 240u);
    ASSERT_EQ(viewer.height, 135u);
    ASSERT_EQ(viewer.pixels.size(), render.pixels.size());
    const double differing = differingFraction(viewer, render);
    std::printf("%s %s: %.4f %% of pixels differ from penumbra render\n", scene.c_str(), options.c_str(), 100.0 * differing);
    EXPECT_LT(differing, 0.001);
}

}  // namespace

TEST(Viewer, GeneratedSceneIsPenumbraRendersImage) {
    SKIP_WITHOUT_XVFB();
    expectViewerShowsPenumbraRendersImage("gen:boxes:20", "gen_boxes", kRepeatable);
}

TEST(Viewer, GroundIsPenumbraRendersGround) {
    // --ground on a lone model (the engine, without camera or light): the same plane, the same framing.
    SKIP_WITHOUT_XVFB();
    expectViewerShowsPenumbraRendersImage(kDefaultFieldModel, "ground", "--ground " + kRepeatable);
}
