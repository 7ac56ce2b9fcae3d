#include "viewer/viewer_options.h"

#include <CLI/CLI.hpp>

#include "penumbra/error.h"

namespace penumbra::viewer {

namespace {

constexpr const char* kViewNames[kViewModes] = {"final", "shadow", "cascades", "atlas", "frusta", "reference"};

constexpr const char* kControls = R"(
Controls:
  W A S D      fly (fly camera); Q / E down / up; Shift faster; mouse wheel sets the speed
  right mouse  look around (fly) or orbit (orbit camera); middle mouse pans (orbit)
  O            orbit camera around the scene, F frames the scene (orbit)
  C            next camera: the scene's (its node named camera, else its first camera, else an automatic
               framing), then every glTF camera
               (the Penumbra panel's camera list picks one by name)
  P            start / stop recording the camera path (into --record-camera-path, else penumbra-camera-path.json)
  1 2 3 4 5 6  view: final, shadow term, cascades, atlas overlay, cascade frusta and culling spheres of the
               camera seen from outside (the fly camera moves out; leaving the view brings it back),
               reference difference; [ / ] previous / next light
  T            reference view: trace the ray-traced reference for this camera and light (a progress bar),
               then show penumbra compare's picture (false shadow red, false lit cyan); moving drops it
  Tab          show / hide the inspector and stats panels
  F12          save a screenshot (penumbra-viewer-N.png in the working directory; one line on stdout)
  Esc          quit
  R            reload the scene file now
The scene file reloads when it changes on disk (checked every --watch-poll-ms), keeping the camera, the
settings and the view; a file that does not load leaves the old scene and shows why. Drop a .gltf / .glb
on the window, or use File > Open, to open another; File > Save scene writes the scene with its edited
shadow extras as glTF.)";

}  // namespace

const char* viewModeName(ViewMode mode) { return kViewNames[int(mode)]; }

std::optional<ViewMode> parseViewMode(const std::string& name) {
    for (int i = 0; i < kViewModes; ++i)
        if (name == kViewNames[i]) return ViewMode(i);
    return std::nullopt;
}

std::optional<ViewerOptions> parseViewerOptions(int argc, char** argv) {
    CLI::App app{"penumbra-viewer: an interactive window on Penumbra's real-time shadows, with an inspector"};
    app.footer(kControls);
    ViewerOptions options;
    std::string view = "final";
    app.add_option("scene", options.scenePath,
                   "glTF 2.0 scene (.gltf or .glb), gen:field:N[:S[:P]] or gen:boxes:N[:P]; the built-in demo scene if omitted");
    app.add_flag("--ground", options.ground,
                 "add a grey ground plane under every scene opened (4x its width, at its lowest point)");
    app.add_option("--asset-root", options.assetRoot,
                   "folder the external buffers and images of every scene opened may come from (default: the scene "
                   "file's own folder)");
    std::vector<std::string> limits;
    app.add_option("--limit", limits,
                   "raise or lower a budget of every scene opened, NAME=VALUE with an optional K/M/G: fileBytes, "
                   "imageBytes, textureBytes, vertices, indices, nodes, nodeDepth, lights, jsonDepth (docs/security.md)");
    app.add_option("--settings", options.settingsPath, "settings JSON file (the same as penumbra render --settings)");
    app.add_option("--set", options.overrides, "override one setting, e.g. shadows.directional.cascadeCount=2");
    app.add_option("--device", options.device, "Vulkan device: auto | gpu | cpu | N")->default_val("auto");
    app.add_option("--width", options.width, "window width in pixels")->check(CLI::Range(16u, 16384u));
    app.add_option("--height", options.height, "window height in pixels")->check(CLI::Range(16u, 16384u));
    app.add_option("--present", options.present,
                   "present mode: fifo (vsync) | mailbox (fifo, with a warning, where the window's surface lacks it)")
        ->check(CLI::IsMember({"fifo", "mailbox"}));
    app.add_flag("--validation", options.validation, "enable the Vulkan validation layers (a message fails the exit code)");
    app.add_option("--screenshot", options.screenshotPath, "render --frames frames, save the last one as PNG, exit");
    app.add_option("--frames", options.frames, "frames to render before --screenshot (default 5)")
        ->check(CLI::Range(1u, 100000u));
    app.add_option("--view", view,
                   "first view: final | shadow | cascades | atlas | frusta | reference (with --screenshot: traced first)")
        ->check(CLI::IsMember(std::vector<std::string>(std::begin(kViewNames), std::end(kViewNames))));
    app.add_option("--light", options.light, "light (index in KHR_lights_punctual) of the shadow and cascade views");
    app.add_flag("--panels", options.panels, "with --screenshot: show the panels in it too");
    app.add_option("--camera-path", options.cameraPath,
                   "play a recorded camera path (JSON); with --screenshot, frame i of N shows i / (N - 1) of it");
    app.add_option("--record-camera-path", options.recordCameraPath,
                   "record the camera path from the first frame into this JSON file (P stops and starts)");
    app.add_option("--compare-settings", options.compareSettingsPath,
                   "split screen: the right half of the final, shadow and cascades views rendered with this settings "
                   "JSON (--set applies to the left half only)");
    app.add_option("--watch-poll-ms", options.watchPollMs,
                   "check the scene file for changes every N ms and reload it (0: every frame; default 250)")
        ->check(CLI::Range(0u, 3600000u));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        app.exit(e);
        return std::nullopt;
    } catch (const CLI::ParseError& e) {
        throw Error(std::string(e.what()) + " (see penumbra-viewer --help)");
    }
    options.view = *parseViewMode(view);
    for (const std::string& limit : limits) setSceneLimit(options.limits, limit);
    return options;
}

}  // namespace penumbra::viewer
