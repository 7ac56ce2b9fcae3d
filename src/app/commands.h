#pragma once
// The CLI's commands, callable from tests too. Each returns the process exit code and throws
// penumbra::Error for user mistakes (the caller prints the one-line message).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/camera.h"
#include "penumbra/device.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

namespace penumbra {

struct RenderOptions {
    std::string scenePath;  // empty: built-in demo scene; gen:field:N[:S[:P]], gen:boxes:N[:P]: built-in scale scenes
    std::string model;      // the glTF gen:field copies (empty: the default engine model)
    bool ground = false;    // --ground: addGroundPlane under the scene
    std::string assetRoot;  // --asset-root: the folder a scene's external files may come from ("" = the scene's folder)
    std::vector<std::string> limits;  // --limit NAME=VALUE: the scene budgets (penumbra/scene_limits.h)
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string settingsPath;
    std::vector<std::string> overrides;
    std::string device = "auto";
    std::string raster;  // --raster: shorthand for --set shadows.raster=...
    std::string mainView;  // --main-view: shorthand for --set render.mainView=...
    bool validation = false;
    bool spinWait = false;  // --spin-wait (bench): DeviceOptions::spinWait
    uint32_t light = 0;
    std::string outputPath;
    std::string aov;
    std::string dumpAtlasPath;
    std::string statsPath;
    std::string maskPath;
    std::string diffPath;
    bool json = false;
    bool shimmer = false;  // compare: also measure shimmer with the camera moved 2 cm to its right
    uint32_t softSamples = 0;  // reference / compare: trace the light as a disk with N rays per pixel
};

// `penumbra bench` only.
struct BenchOptions {
    uint32_t frames = 100;
    uint32_t warmup = 10;
    std::string camera = "static";  // static | orbit
    std::string jsonPath;           // "" = none, "-" = stdout
    std::string frameTimesPath;     // --frame-times: one CSV row per timed frame ("" = none)
    bool vary = false;              // --vary-settings
    uint32_t varyEvery = 100;       // --vary-every
    uint32_t varyPeriod = 0;        // frames between changes of --vary-settings (0 = no changes)
    double lightMotion = 0.0;       // --light-motion: degrees the directional lights turn per frame (0 = still)
    double moveObjects = 0.0;       // --move-objects: the share of instances that move every frame (0 = none)
    int pinCpu = -1;                // --pin-cpu: the logical CPU the frame thread runs on while timed (-1 = any)
};

// The scene the options name (file, demo or gen:), its warnings printed on stderr.
Scene loadSceneFor(const RenderOptions& options);
// The device the options choose; a failure to make it names the --device choice (unless auto).
Device openDevice(const RenderOptions& options);
// Throws Error "--light N does not exist (the scene has M lights)" when the scene has no light N.
void checkLightOption(const RenderOptions& options, const Scene& scene);
// The render request the options describe: size, AOV (--aov, --light) and atlas capture.
RenderRequest makeRenderRequest(const RenderOptions& options);
Settings loadSettings(const RenderOptions& options);
// `settings` with the scene-dependent defaults for the keys the user left out (applySceneDefaults:
// shadows.maxDistance from the scene's extent), each change as a warning on stderr.
Settings withSceneDefaults(Settings settings, const Scene& scene, const CameraView& view);

// What a command that renders the scene's camera view sets up, in this order: the settings (checked
// before the device starts), the device, the renderer, the request, the view and the settings with
// the scene defaults.
struct ViewRender {
    explicit ViewRender(const RenderOptions& options);
    Settings userSettings;
    Device device;
    Renderer renderer;
    RenderRequest request;
    CameraView view;
    Settings settings;
};

int runRenderCommand(const RenderOptions& options);
int runReferenceCommand(const RenderOptions& options);
int runCompareCommand(const RenderOptions& options);
int runBenchCommand(const RenderOptions& options, const BenchOptions& bench);
int runDevicesCommand();
// Writes the scene the options name (a file, the demo or a gen: scene) as .gltf or .glb.
int runExportCommand(const RenderOptions& options);
int runDiffCommand(const std::string& pathA, const std::string& pathB);
// Renders `frames` frames and prints the last one's frame graph as "mermaid" or "dot" on stdout.
int runGraphCommand(const RenderOptions& options, const std::string& format, uint32_t frames);
// The settings reference (docs/settings.md) as Markdown, or with `json` every key's default as a
// settings file; both made from the key table.
int runSettingsCommand(bool json);

}  // namespace penumbra
