#pragma once
// Renders a Scene with the shadow system: the Frame orders the passes (shadow atlases, optional
// depth prepass and screen-space shadow resolve, opaque + unlit, transparent) and reads back the
// colour image or a debug AOV.
#include <memory>
#include <string>
#include <vector>

#include "app/settings.h"
#include "core/image.h"
#include "gpu/device.h"
#include "scene/camera_view.h"
#include "scene/scene.h"

namespace penumbra {

enum class OutputMode { Color, ShadowAov, CascadesAov };

struct RenderRequest {
    uint32_t width = 1280;
    uint32_t height = 720;
    OutputMode output = OutputMode::Color;
    uint32_t aovLight = 0;       // index into Scene::lights for --aov shadow / cascades
    bool captureAtlas = false;   // fill RenderResult::atlas (--dump-atlas)
};

struct RenderStats {
    std::vector<gpu::PassTiming> gpuTimings;
    std::vector<std::string> warnings;
    double cpuPlanMilliseconds = 0.0;
    std::string shadowStatsJson = "{}";  // the shadow planner's stats (lights reserved, tiles, draws)
};

struct RenderResult {
    Image image;  // RGB colour (sRGB) or 1-channel AOV
    Image atlas;  // 1-channel depth of the shadow atlases when requested
    RenderStats stats;
};

class Renderer {
public:
    Renderer(gpu::Device& device, const Scene& scene);
    ~Renderer();
    RenderResult render(const RenderRequest& request, const Settings& settings);
    RenderResult render(const RenderRequest& request, const Settings& settings, const CameraView& view);

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace penumbra
