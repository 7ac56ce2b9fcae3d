// `penumbra bench`: renders the same frame repeatedly and prints GPU time per pass (timestamps) and
// CPU planning time, as median and minimum over the frames. Numbers, not pass/fail.
#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include "app/commands.h"
#include "gpu/device.h"
#include "render/renderer.h"

namespace penumbra {

namespace {

struct Series {
    std::vector<double> values;
    double median() {
        std::sort(values.begin(), values.end());
        return values.empty() ? 0.0 : values[values.size() / 2];
    }
    double minimum() const { return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end()); }
};

}  // namespace

int runBenchCommand(const RenderOptions& options, uint32_t frames) {
    const Settings settings = loadSettings(options);
    const Scene scene = loadSceneOrDemo(options.scenePath);
    gpu::Device device({options.device, options.validation, true});
    Renderer renderer(device, scene);
    const RenderRequest request = makeRenderRequest(options);
    std::map<std::string, Series> gpuMs;
    Series planMs;
    renderer.render(request, settings);  // warm-up: pipelines, caches
    for (uint32_t i = 0; i < frames; ++i) {
        const RenderResult result = renderer.render(request, settings);
        for (const auto& timing : result.stats.gpuTimings) gpuMs[timing.name].values.push_back(timing.milliseconds);
        planMs.values.push_back(result.stats.cpuPlanMilliseconds);
    }
    std::printf("device: %s (%s)\nframe: %ux%u, %u frames after 1 warm-up\n", device.info().name.c_str(),
                device.info().driver.c_str(), request.width, request.height, frames);
    std::printf("%-24s %12s %12s\n", "pass", "median ms", "min ms");
    double total = 0.0;
    for (auto& [name, series] : gpuMs) {
        const double median = series.median();
        total += median;
        std::printf("gpu %-20s %12.4f %12.4f\n", name.c_str(), median, series.minimum());
    }
    std::printf("gpu %-20s %12.4f\n", "total (sum of medians)", total);
    std::printf("cpu %-20s %12.4f %12.4f\n", "shadow plan", planMs.median(), planMs.minimum());
    return 0;
}

}  // namespace penumbra
