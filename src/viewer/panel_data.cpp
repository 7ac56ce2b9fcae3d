#include "viewer/panel_data.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace penumbra::viewer {

SplitBar splitBarOf(const Settings& settings, const std::string& shadowStatsJson) {
    const DirectionalShadowSettings& directional = settings.shadows.directional;
    SplitBar bar;
    if (directional.cascadeSplits == CascadeSplitMode::Manual) {
        for (uint32_t c = 0; c + 1 < directional.cascadeCount; ++c) bar.ends.push_back(directional.cascadeRatios[c]);
        bar.ends.push_back(1.0f);
        return bar;
    }
    bar.computed = true;
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson, nullptr, false);
    if (stats.is_discarded() || !stats.contains("directional")) return bar;
    const auto splits = stats["directional"].value("cascadeSplits", std::vector<float>{});
    const float distance = settings.shadows.maxDistance;
    float last = 0.0f;
    for (float metres : splits) {
        last = std::clamp(distance > 0.0f ? metres / distance : 1.0f, last, 1.0f);
        bar.ends.push_back(last);
    }
    return bar;
}

std::string shadowLightCounts(const std::string& shadowStatsJson) {
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson, nullptr, false);
    if (stats.is_discarded() || !stats.contains("directional") || !stats.contains("other")) return "";
    const nlohmann::json &directional = stats["directional"], &other = stats["other"];
    const int sunsReserved = directional.value("lightsReserved", 0);
    const int sunsDropped = std::max(directional.value("lightsConsidered", 0) - sunsReserved, 0);
    return "directional lights reserved " + std::to_string(sunsReserved) + ", dropped " + std::to_string(sunsDropped) +
           "; spot/point reserved " + std::to_string(other.value("lightsReserved", 0)) + ", dropped " +
           std::to_string(other.value("lightsDropped", 0));
}

std::vector<std::string> cameraChoices(const Scene& scene) {
    std::vector<std::string> choices = {"scene camera"};
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        choices.push_back(scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : scene.cameras[i].name);
    return choices;
}

}  // namespace penumbra::viewer
