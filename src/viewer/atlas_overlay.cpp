#include "viewer/atlas_overlay.h"

#include <algorithm>

namespace penumbra::viewer {

namespace {

constexpr const char* kCubeFaces[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

glm::vec2 tileCorner(uint32_t tile, uint32_t split, uint32_t tileSize) {
    return glm::vec2(float((tile % split) * tileSize), float((tile / split) * tileSize));
}

}  // namespace

std::vector<AtlasTileLabel> atlasTileLabels(const ShadowPlanStats& shadows, const Scene& scene) {
    std::vector<AtlasTileLabel> labels;
    const DirectionalShadowStats& directional = shadows.directional;
    const auto& sceneLights = directional.reservedLights;  // per slot
    const uint32_t tiles = directional.tiles, lights = sceneLights.size();
    const uint32_t split = std::max(directional.split, 1u), tileSize = directional.tileSize;
    const uint32_t cascades = lights > 0 ? tiles / lights : 0;
    for (uint32_t t = 0; t < tiles && cascades > 0 && t / cascades < sceneLights.size(); ++t) {
        const glm::vec2 corner = tileCorner(t, split, tileSize);
        labels.push_back({corner, corner + glm::vec2(float(tileSize)),
                          "sun" + std::to_string(sceneLights[t / cascades]) + " c" + std::to_string(t % cascades)});
    }
    const float otherLeft = tiles > 0 ? float(directional.atlasSize) : 1.0f;
    const OtherShadowStats& other = shadows.other;
    const uint32_t otherSplit = std::max(other.split, 1u), otherTileSize = other.tileSize;
    uint32_t tile = 0;
    for (const uint32_t lightIndex : other.reservedLights) {
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
