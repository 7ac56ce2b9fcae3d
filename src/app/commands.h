#pragma once
// The CLI's commands, callable from tests too. Each returns the process exit code and throws
// penumbra::Error for user mistakes (the caller prints the one-line message).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/settings.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace penumbra {

struct RenderOptions {
    std::string scenePath;  // empty: built-in demo scene
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string settingsPath;
    std::vector<std::string> overrides;
    std::string device = "auto";
    bool validation = false;
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

Scene loadSceneOrDemo(const std::string& path);
// The render request the options describe: size, AOV (--aov, --light) and atlas capture.
RenderRequest makeRenderRequest(const RenderOptions& options);
Settings loadSettings(const RenderOptions& options);

int runRenderCommand(const RenderOptions& options);
int runReferenceCommand(const RenderOptions& options);
int runCompareCommand(const RenderOptions& options);
int runBenchCommand(const RenderOptions& options, uint32_t frames);
int runDevicesCommand();
int runDiffCommand(const std::string& pathA, const std::string& pathB);

}  // namespace penumbra
