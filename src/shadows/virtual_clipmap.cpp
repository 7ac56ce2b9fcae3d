#include "shadows/virtual_clipmap.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "shadows/cascades.h"

namespace penumbra {

namespace {

int32_t floorToInt(float value) { return int32_t(std::floor(value)); }

// a mod n in [0, n) for negative a too.
uint32_t wrap(int32_t a, uint32_t n) {
    const int32_t m = a % int32_t(n);
    return uint32_t(m < 0 ? m + int32_t(n) : m);
}

PageRect intersect(const PageRect& a, const PageRect& b) {
    return {glm::max(a.min, b.min), glm::min(a.max, b.max)};
}

}  // namespace

glm::mat4 clipmapRotationFromWorld(const glm::vec3& wsLightDirection) {
    // About light-space z, the light's axis: x' = c x + s y, y' = -s x + c y.
    const glm::mat4 turned = glm::rotate(glm::mat4(1.0f), -glm::radians(kClipmapGridTurnDegrees), glm::vec3(0.0f, 0.0f, 1.0f));
    return turned * lightRotationFromWorld(wsLightDirection);
}

uint32_t pagesPerSide(const VirtualClipmapConfig& config) {
    PENUMBRA_ASSERT(config.pageSize > 0 && config.resolution % config.pageSize == 0);
    return config.resolution / config.pageSize;
}

bool PageRect::contains(const PageRect& other) const {
    return !other.empty() && other.min.x >= min.x && other.min.y >= min.y && other.max.x <= max.x &&
           other.max.y <= max.y;
}

uint32_t PageRect::pageCount() const {
    return empty() ? 0u : uint32_t(max.x - min.x + 1) * uint32_t(max.y - min.y + 1);
}

ClipmapLevel placeClipmapLevel(const VirtualClipmapConfig& config, uint32_t level, const glm::vec2& lsCamera) {
    ClipmapLevel placed;
    placed.level = level;
    placed.pagesPerSide = pagesPerSide(config);
    placed.lsSize = std::ldexp(config.firstLevelSize, int(level));
    placed.lsTexelSize = placed.lsSize / float(config.resolution);
    placed.lsPageSize = placed.lsSize / float(placed.pagesPerSide);
    const glm::ivec2 cameraPage = pageOf(placed, lsCamera);
    const int32_t half = int32_t(placed.pagesPerSide / 2);
    placed.window.min = cameraPage - half;
    placed.window.max = placed.window.min + int32_t(placed.pagesPerSide) - 1;
    return placed;
}

glm::ivec2 pageOf(const ClipmapLevel& level, const glm::vec2& lsPosition) {
    return {floorToInt(lsPosition.x / level.lsPageSize), floorToInt(lsPosition.y / level.lsPageSize)};
}

glm::uvec2 pageTableSlot(const ClipmapLevel& level, const glm::ivec2& page) {
    return {wrap(page.x, level.pagesPerSide), wrap(page.y, level.pagesPerSide)};
}

uint32_t levelForFootprint(const VirtualClipmapConfig& config, float wsPixelFootprint) {
    const float firstTexel = config.firstLevelSize / float(config.resolution);
    if (!(wsPixelFootprint > firstTexel)) return 0;
    const float level = std::floor(std::log2(wsPixelFootprint / firstTexel));
    return uint32_t(std::min(level, float(config.levelCount - 1)));
}

PageRect receiverPages(const ClipmapLevel& level, const glm::vec2& lsPosition, float marginTexels) {
    const glm::vec2 margin(marginTexels * level.lsTexelSize);
    return {pageOf(level, lsPosition - margin), pageOf(level, lsPosition + margin)};
}

std::optional<uint32_t> levelForReceiver(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                                         const glm::vec2& lsReceiver, float wsPixelFootprint, float marginTexels) {
    for (uint32_t level = levelForFootprint(config, wsPixelFootprint); level < config.levelCount; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        if (placed.window.contains(receiverPages(placed, lsReceiver, marginTexels))) return level;
    }
    return std::nullopt;
}

PageRect pagesTouchedByBounds(const ClipmapLevel& level, const Aabb& lsBounds) {
    if (!lsBounds.valid()) return {};
    const PageRect touched{pageOf(level, glm::vec2(lsBounds.min)), pageOf(level, glm::vec2(lsBounds.max))};
    const PageRect clipped = intersect(touched, level.window);
    return clipped.empty() ? PageRect{} : clipped;
}

uint32_t casterPageRects(const VirtualClipmapConfig& config, const glm::mat4& lightRotation, const glm::vec2& lsCamera,
                         const Aabb& wsBounds, LevelPageRect* out) {
    if (!wsBounds.valid()) return 0;
    const Aabb lsBounds = wsBounds.transformed(lightRotation);
    uint32_t count = 0;
    for (uint32_t level = 0; level < config.levelCount; ++level) {
        const PageRect pages = pagesTouchedByBounds(placeClipmapLevel(config, level, lsCamera), lsBounds);
        if (!pages.empty()) out[count++] = {level, pages};
    }
    return count;
}

void packClipmapWindows(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                        gpu_data::VirtualPageLevelWindow* levels) {
    PENUMBRA_ASSERT(config.levelCount <= gpu_data::kVirtualPageMaxLevels);
    for (uint32_t level = 0; level < config.levelCount; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        const glm::uvec2 slot = pageTableSlot(placed, placed.window.min);
        levels[level] = {placed.window.min.x, placed.window.min.y, slot.x, slot.y};
    }
}

}  // namespace penumbra
