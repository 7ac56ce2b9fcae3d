// penumbra-viewer's real window, driven as a user would: run interactively (no --screenshot) under
// xvfb-run with the validation layers on, with keys and window changes sent by xdotool (XTEST, as a
// keyboard would); F12 saves penumbra-viewer-N.png in the working directory and says so on stdout,
// which is when the next step is sent. Each run ends with Esc: exit code 0, no validation message.
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "viewer_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

bool hasXdotool() { return std::system("command -v xdotool >/dev/null 2>&1") == 0; }

#define SKIP_WITHOUT_XDOTOOL()                                                                             \
    SKIP_WITHOUT_XVFB();                                                                                   \
    if (!hasXdotool()) GTEST_SKIP() << "xdotool is not installed (scripts/setup.sh installs it)"

// A step: xdotool commands (each one invocation; %W is the viewer's window), sent once the viewer has
// opened its scene (the first step) or saved the previous step's screenshot. Every step but the last
// ends with F12; the last is Escape.
using Step = std::vector<std::string>;

struct WindowRun {
    CliRun run;
    std::vector<Image> screenshots;  // penumbra-viewer-0.png, -1.png, ... as the steps saved them
    bool allStepsSent = false;
};

// The display's address, printed by the shell xvfb-run starts before it becomes the viewer.
constexpr const char* kDisplayLine = "penumbra-test-display ";

class WindowDriver {
public:
    // The window's id: polled (xdotool search) until the viewer's window is visible, at most 120 s.
    bool findWindow() {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
        while (std::chrono::steady_clock::now() < deadline) {
            const CliRun found = runProgram("xdotool", "search --onlyvisible --name '^penumbra-viewer$'", environment_);
            if (found.exitCode == 0 && !found.out.empty()) {
                window_ = found.out.substr(0, found.out.find('\n'));
                return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        return false;
    }

    bool send(const Step& step) {
        for (std::string command : step) {
            for (size_t at = command.find("%W"); at != std::string::npos; at = command.find("%W")) command.replace(at, 2, window_);
            const CliRun run = runProgram("xdotool", command, environment_);
            EXPECT_EQ(run.exitCode, 0) << "xdotool " << command << ": " << run.err;
            if (run.exitCode != 0) return false;
        }
        return true;
    }

    void setDisplay(const std::string& line) {
        std::string display, authority;
        std::istringstream(line.substr(std::string(kDisplayLine).size())) >> display >> authority;
        environment_ = "DISPLAY=" + display + " XAUTHORITY=" + authority;
    }

private:
    std::string environment_, window_;
};

// Runs the viewer on `scene` in a window of width x height with `options` and sends `steps`.
WindowRun driveViewer(const std::string& scene, const std::string& options, uint32_t width, uint32_t height,
                      const std::vector<Step>& steps) {
    const fs::path dir = tempPath("window_run");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string viewer = std::string(kViewer) + " " + scene + " --device cpu --validation --width " +
                               std::to_string(width) + " --height " + std::to_string(height) + " " + options;
    // The viewer's own time limit: a lost key would otherwise leave it running.
    const std::string command = "cd " + dir.string() + " && timeout 300 " + xvfbRun() + " sh -c 'echo \"" + kDisplayLine +
                                "$DISPLAY $XAUTHORITY\"; exec " + viewer + "'";
    WindowRun result;
    WindowDriver driver;
    size_t next = 0;
    auto sendNext = [&] {
        if (next < steps.size() && driver.send(steps[next])) ++next;
        result.allStepsSent = next == steps.size();
    };
    result.run = followStdout(command, [&](const std::string& line) {
        if (line.rfind(kDisplayLine, 0) == 0) driver.setDisplay(line);
        if (line.find("penumbra-viewer: opened ") == 0) {
            if (driver.findWindow() && driver.send({"windowfocus --sync %W"})) sendNext();
            else ADD_FAILURE() << "no visible penumbra-viewer window within 120 s";
        }
        if (line.find("penumbra-viewer: saved penumbra-viewer-") == 0) {
            const size_t name = line.find("penumbra-viewer-");
            const fs::path shot = dir / line.substr(name, line.find(".png") + 4 - name);
            result.screenshots.push_back(readPng(shot.string()));
            sendNext();
        }
    });
    EXPECT_TRUE(result.allStepsSent) << result.run.out << result.run.err;
    EXPECT_EQ(result.run.exitCode, 0) << result.run.err;
    EXPECT_EQ(result.run.err.find("validation"), std::string::npos) << result.run.err;
    return result;
}

const Step kScreenshot = {"key F12"};
const Step kQuit = {"key Escape"};

}  // namespace

TEST(ViewerWindow, ResizedWindowScreenshotsAtItsNewSizeAndEscapeQuits) {
    SKIP_WITHOUT_XDOTOOL();
    const WindowRun window = driveViewer(kScenes + "cube.gltf", "", 320, 180,
                                         {kScreenshot, {"windowsize --sync %W 208 128", "key F12"}, kQuit});
    ASSERT_EQ(window.screenshots.size(), 2u);
    EXPECT_EQ(window.screenshots[0].width, 320u);
    EXPECT_EQ(window.screenshots[0].height, 180u);
    EXPECT_EQ(window.screenshots[1].width, 208u) << "the screenshot after the resize";
    EXPECT_EQ(window.screenshots[1].height, 128u) << "the screenshot after the resize";
}

TEST(ViewerWindow, TabHidesThePanels) {
    SKIP_WITHOUT_XDOTOOL();
    const std::string scene = kScenes + "cube.gltf";
    const WindowRun window = driveViewer(scene, kRepeatable, 320, 180, {kScreenshot, {"key Tab", "key F12"}, kQuit});
    const Image plain = viewerScreenshot(scene, "window_plain.png", kRepeatable, 320, 180);
    ASSERT_EQ(window.screenshots.size(), 2u);
    ASSERT_EQ(window.screenshots[0].pixels.size(), plain.pixels.size());
    ASSERT_EQ(window.screenshots[1].pixels.size(), plain.pixels.size());
    EXPECT_GT(differingFraction(window.screenshots[0], plain), 0.2) << "no panels over the view before Tab";
    EXPECT_LT(differingFraction(window.screenshots[1], plain), 0.001) << "panels left over the view after Tab";
}

TEST(ViewerWindow, Key3ShowsTheCascadesView) {
    SKIP_WITHOUT_XDOTOOL();
    const std::string scene = kScenes + "cube.gltf";
    const WindowRun window = driveViewer(scene, kRepeatable, 320, 180, {{"key Tab", "key 3", "key F12"}, kQuit});
    const Image cascades = viewerScreenshot(scene, "window_cascades.png", "--view cascades " + kRepeatable, 320, 180);
    const Image final = viewerScreenshot(scene, "window_final.png", kRepeatable, 320, 180);
    ASSERT_EQ(window.screenshots.size(), 1u);
    ASSERT_EQ(window.screenshots[0].pixels.size(), cascades.pixels.size());
    ASSERT_GT(differingFraction(cascades, final), 0.2) << "the views must differ for the test to tell them apart";
    EXPECT_LT(differingFraction(window.screenshots[0], cascades), 0.001);
}

namespace {

// cube.gltf with a second camera node, "side", after its own: the glTF cameras are [camera, side].
// With `sideAsSceneCamera` the node "camera" (the scene's camera) is placed where "side" is.
std::string cubeWithSideCamera(bool sideAsSceneCamera) {
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(kScenes + "cube.gltf"));
    nlohmann::json side;
    for (const nlohmann::json& node : gltf["nodes"])
        if (node.value("name", "") == "camera") side = node;
    side["name"] = "side";
    side["matrix"][12] = 1.0f;  // 3 m to the left of cube.gltf's camera, looking the same way
    for (nlohmann::json& node : gltf["nodes"])
        if (sideAsSceneCamera && node.value("name", "") == "camera") node["matrix"] = side["matrix"];
    gltf["nodes"].push_back(side);
    gltf["scenes"][gltf.value("scene", 0)]["nodes"].push_back(gltf["nodes"].size() - 1);
    return gltf.dump();
}

}  // namespace

TEST(ViewerWindow, KeyCStepsToTheNextGltfCamera) {
    SKIP_WITHOUT_XDOTOOL();
    const fs::path scene = writeText("two_cameras.gltf", cubeWithSideCamera(false));
    const fs::path fromSide = writeText("side_camera.gltf", cubeWithSideCamera(true));
    // C: the scene's camera -> glTF camera 0 ("camera", the same) -> glTF camera 1 ("side").
    const WindowRun window = driveViewer(scene.string(), kRepeatable, 320, 180, {{"key Tab", "key c", "key c", "key F12"}, kQuit});
    const Image side = viewerScreenshot(fromSide.string(), "window_side.png", kRepeatable, 320, 180);
    const Image front = viewerScreenshot(scene.string(), "window_front.png", kRepeatable, 320, 180);
    ASSERT_EQ(window.screenshots.size(), 1u);
    ASSERT_EQ(window.screenshots[0].pixels.size(), side.pixels.size());
    ASSERT_GT(differingFraction(side, front), 0.1) << "the cameras must see different images for the test to tell them apart";
    EXPECT_LT(differingFraction(window.screenshots[0], side), 0.001);
}

TEST(ViewerWindow, UnmappedWindowDrawsAgainOnceMappedBack) {
    SKIP_WITHOUT_XDOTOOL();
    // Xvfb runs no window manager, so the window is hidden the way one minimizes it on X11: unmapped.
    const Step hideAndShow = {"windowunmap --sync %W", "windowmap --sync %W", "windowfocus --sync %W", "key F12"};
    const WindowRun window = driveViewer(kScenes + "cube.gltf", "", 240, 135, {hideAndShow, kQuit});
    ASSERT_EQ(window.screenshots.size(), 1u);
    EXPECT_EQ(window.screenshots[0].width, 240u);
}
