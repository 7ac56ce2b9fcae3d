#include "viewer/atlas_overlay.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace penumbra::viewer {

namespace {

constexpr const char* kCubeFaces[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

glm::vec2 tileCorner(uint32_t tile, uint32_t split, uint32_t tileSize) {
    return glm::vec2(float((tile % split) * tileSize), float((tile / split) * tileSize));
}

}  // namespace

std::vector<AtlasTileLabel> atlasTileLabels(const std::string& shadowStatsJson, const Scene& scene) {
    std::vector<AtlasTileLabel> labels;
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson, nullptr, false);
    if (stats.is_discarded() || !stats.contains("directional")) return labels;
    const nlohmann::json& directional = stats["directional"];
    const uint32_t tiles = directional.value("tiles", 0u), lights = directional.value("lightsReserved", 0u);
    const uint32_t split = std::max(directional.value("split", 1u), 1u), tileSize = directional.value("tileSize", 0u);
    const uint32_t cascades = lights > 0 ? tiles / lights : 0;
    const auto sceneLights = directional.value("reservedLights", std::vector<uint32_t>{});  // per slot
    for (uint32_t t = 0; t < tiles && cascades > 0 && t / cascades < sceneLights.size(); ++t) {
        const glm::vec2 corner = tileCorner(t, split, tileSize);
        labels.push_back({corner, corner + glm::vec2(float(tileSize)),
                          "sun" + std::to_string(sceneLights[t / cascades]) + " c" + std::to_string(t % cascades)});
    }
    const float otherLeft = tiles > 0 ? float(directional.value("atlasSize", 0u)) : 1.0f;
    const nlohmann::json other = stats.value("other", nlohmann::json::object());
    const uint32_t otherSplit = std::max(other.value("split", 1u), 1u), otherTileSize = other.value("tileSize", 0u);
    uint32_t tile = 0;
    for (const auto& lightIndex : other.value("reservedLights", std::vector<uint32_t>{})) {
        const bool point = lightIndex < scene.lights.size() && scene.lights[lightIndex].type == LightType::Point;
        for (uint32_t face = 0; face < (point ? 6u : 1u); ++face, ++tile) {
            const glm::vec2 corner = glm::vec2(otherLeft, 0.0f) + tileCorner(tile, otherSplit, otherTileSize);
            std::string text = (point ? "point" : "spot") + std::to_string(lightIndex);
            if (point) text += std::string(" ") + kCubeFaces[face];
            labels.push_back({corner, corner + glm::vec2(float(otherTileSize)), text});
        }
    }
    return labels;
}

}  // namespace penumbra::viewer
