#include "viewer/panel_data.h"

#include <algorithm>

namespace penumbra::viewer {

SplitBar splitBarOf(const Settings& settings, const ShadowPlanStats& shadows) {
    const DirectionalShadowSettings& directional = settings.shadows.directional;
    SplitBar bar;
    if (directional.cascadeSplits == CascadeSplitMode::Manual) {
        for (uint32_t c = 0; c + 1 < directional.cascadeCount; ++c) bar.ends.push_back(directional.cascadeRatios[c]);
        bar.ends.push_back(1.0f);
        return bar;
    }
    bar.computed = true;
    const float distance = settings.shadows.maxDistance;
    float last = 0.0f;
    for (float metres : shadows.directional.cascadeSplits) {
        last = std::clamp(distance > 0.0f ? metres / distance : 1.0f, last, 1.0f);
        bar.ends.push_back(last);
    }
    return bar;
}

std::string shadowLightCounts(const ShadowPlanStats& shadows) {
    const int sunsReserved = int(shadows.directional.reservedLights.size());
    const int sunsDropped = std::max(int(shadows.directional.lightsConsidered) - sunsReserved, 0);
    return "directional lights reserved " + std::to_string(sunsReserved) + ", dropped " + std::to_string(sunsDropped) +
           "; spot/point reserved " + std::to_string(shadows.other.reservedLights.size()) + ", dropped " +
           std::to_string(shadows.other.lightsDropped);
}

std::string countList(const std::vector<uint64_t>& counts) {
    std::string text = "[";
    for (size_t i = 0; i < counts.size(); ++i) text += (i ? ", " : "") + std::to_string(counts[i]);
    return text + "]";
}

std::vector<std::string> cameraChoices(const Scene& scene) {
    std::vector<std::string> choices = {"scene camera"};
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        choices.push_back(scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : scene.cameras[i].name);
    return choices;
}

}  // namespace penumbra::viewer
