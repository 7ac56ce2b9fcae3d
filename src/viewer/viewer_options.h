#pragma once
// The command line of penumbra-viewer: what to open, on which device, and the scripted mode
// (--screenshot FILE --frames N) that CI runs under Xvfb.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/scene_limits.h"

namespace penumbra::viewer {

// Frusta: the cascades of the camera at the moment the view is entered, seen from an outside camera.
// Reference: our shadow term against the ray-traced reference, in penumbra compare --diff's colours.
enum class ViewMode { Final, Shadow, Cascades, Atlas, Frusta, Reference };
constexpr int kViewModes = 6;

const char* viewModeName(ViewMode mode);
std::optional<ViewMode> parseViewMode(const std::string& name);

struct ViewerOptions {
    std::string scenePath;  // file, gen:..., or "" for the built-in demo scene
    bool ground = false;    // --ground: every scene opened gets addGroundPlane
    std::string assetRoot;  // --asset-root: where every scene opened may read external files ("" = its own folder)
    SceneLimits limits;     // --limit NAME=VALUE: the budgets of every scene opened
    std::string settingsPath;
    std::vector<std::string> overrides;  // --set key=value
    std::string device = "auto";
    uint32_t width = 1280, height = 720;
    std::string present = "fifo";  // fifo | mailbox
    bool validation = false;
    std::string screenshotPath;  // scripted: render `frames` frames, save the last one, exit
    uint32_t frames = 5;
    ViewMode view = ViewMode::Final;
    uint32_t light = 0;
    bool panels = false;  // --screenshot: keep the panels (hidden by default so the image is the view alone)
    std::string cameraPath;        // --camera-path: play this recorded path (camera_path.h)
    std::string recordCameraPath;  // --record-camera-path: record from the first frame into this file
    std::string compareSettingsPath;  // --compare-settings: the right half rendered with this settings file
    uint32_t watchPollMs = 250;    // --watch-poll-ms: how often the scene file is checked for changes (0: every frame)
};

// Parses argv. Returns nullopt after printing --help; throws penumbra::Error with one line on a
// bad option.
std::optional<ViewerOptions> parseViewerOptions(int argc, char** argv);

}  // namespace penumbra::viewer
