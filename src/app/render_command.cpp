#include <cstdio>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "penumbra/device.h"
#include "penumbra/error.h"
#include "penumbra/files.h"
#include "penumbra/gltf_writer.h"
#include "penumbra/image_diff.h"
#include "penumbra/renderer.h"
#include "penumbra/scene_loading.h"

namespace penumbra {

Scene loadSceneFor(const RenderOptions& options) {
    SceneSourceOptions source;
    if (!options.model.empty()) source.model = options.model;
    source.addGround = options.ground;
    source.assetRoot = options.assetRoot;
    for (const std::string& limit : options.limits) setSceneLimit(source.limits, limit);
    Scene scene = loadScene(options.scenePath, source);
    for (const std::string& warning : scene.warnings) std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    return scene;
}

Device openDevice(const RenderOptions& options) {
    DeviceOptions device;
    device.device = options.device;
    device.validation = options.validation;
    device.spinWait = options.spinWait;
    try {
        return Device(device);
    } catch (const Error& e) {
        if (options.device == "auto") throw;
        throw Error("--device " + options.device + ": " + e.what());
    }
}

void checkLightOption(const RenderOptions& options, const Scene& scene) {
    if (options.light >= scene.lights.size())
        throw Error("--light " + std::to_string(options.light) + " does not exist (the scene has " +
                    std::to_string(scene.lights.size()) + " lights)");
}

RenderRequest makeRenderRequest(const RenderOptions& options) {
    RenderRequest request;
    request.width = options.width;
    request.height = options.height;
    request.aovLight = options.light;
    if (options.aov == "shadow") request.output = OutputMode::ShadowAov;
    if (options.aov == "cascades") request.output = OutputMode::CascadesAov;
    request.captureAtlas = !options.dumpAtlasPath.empty();
    return request;
}

Settings loadSettings(const RenderOptions& options) {
    Settings settings = options.settingsPath.empty() ? Settings{} : loadSettingsFile(options.settingsPath);
    for (const std::string& assignment : options.overrides) {
        if (assignment.find('=') == std::string::npos)
            throw Error("settings: --set expects key=value, got '" + assignment + "'");
        applySettingOverride(settings, assignment);
    }
    if (!options.raster.empty()) applySettingOverride(settings, "shadows.raster=" + options.raster);
    if (!options.mainView.empty()) applySettingOverride(settings, "render.mainView=" + options.mainView);
    validateSettings(settings);
    return settings;
}

Settings withSceneDefaults(Settings settings, const Scene& scene, const CameraView& view) {
    for (const std::string& warning : applySceneDefaults(settings, scene, view))
        std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    return settings;
}

ViewRender::ViewRender(const RenderOptions& options)
    : userSettings(loadSettings(options)),
      device(openDevice(options)),
      renderer(device, loadSceneFor(options)),
      request(makeRenderRequest(options)),
      view(resolveCameraView(renderer.scene(), request.width, request.height)),
      settings(withSceneDefaults(userSettings, renderer.scene(), view)) {}

namespace {

std::string statsJson(const RenderResult& result, const Device& device, const RenderOptions& options) {
    nlohmann::json stats = nlohmann::json::parse(toJson(result.stats));
    stats["device"] = {{"name", device.info().name}, {"driver", device.info().driver}, {"cpu", device.info().isCpu}};
    stats["width"] = options.width;
    stats["height"] = options.height;
    return stats.dump(2);
}

}  // namespace

int runRenderCommand(const RenderOptions& options) {
    checkWritable(options.outputPath);
    checkWritable(options.dumpAtlasPath);
    checkWritable(options.statsPath);
    ViewRender setup(options);
    const Device& device = setup.device;
    const RenderRequest& request = setup.request;
    if (!options.aov.empty() && !setup.renderer.scene().lights.empty()) checkLightOption(options, setup.renderer.scene());
    const RenderResult result = setup.renderer.render(request, setup.settings, setup.view);
    for (const std::string& warning : result.stats.warnings) std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    writePng(result.image, options.outputPath);
    if (request.captureAtlas) writePng(result.atlas, options.dumpAtlasPath);
    if (!options.statsPath.empty()) {
        const std::string json = statsJson(result, device, options);
        if (options.statsPath == "-") {
            std::printf("%s\n", json.c_str());
        } else {
            writeTextFile(options.statsPath, json + "\n");
        }
    }
    if (options.validation && device.validationMessageCount() > 0)
        throw Error(std::to_string(device.validationMessageCount()) + " Vulkan validation messages (see above)");
    return 0;
}

int runExportCommand(const RenderOptions& options) {
    checkWritable(options.outputPath);
    writeGltfScene(loadSceneFor(options), options.outputPath);
    return 0;
}

int runDiffCommand(const std::string& pathA, const std::string& pathB) {
    const Image a = readPng(pathA);  // A first, so a bad A is the one reported
    const Image b = readPng(pathB);
    std::printf("%s\n", toJson(diffImages(a, b)).c_str());
    return 0;
}

int runDevicesCommand() {
    for (const DeviceInfo& info : Device::list())
        std::printf("%u: %s (%s)%s\n", info.index, info.name.c_str(), info.driver.c_str(), info.isCpu ? " [cpu]" : "");
    return 0;
}

}  // namespace penumbra
