#include "shadows/virtual_page_marking.h"

#include <algorithm>
#include <bit>
#include <span>
#include <cmath>

#include "core/error.h"
#include "shadows/visible_surfaces.h"
#include "virtual_page_structs.h"

namespace penumbra {

namespace {

uint32_t bitOf(const VirtualPageRequests& requests, uint32_t level, const glm::uvec2& slot) {
    PENUMBRA_ASSERT(level < requests.levelCount && slot.x < requests.pagesPerSide && slot.y < requests.pagesPerSide);
    return gpu_data::virtualPageBit(level, requests.pagesPerSide, slot.x, slot.y);
}

// Every page of the level a receiver at lsPosition samples, with its filter's reach, and of its fallback level.
void markReceiver(VirtualPageRequests& requests, const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                  const glm::vec2& lsPosition, float wsFootprint, float marginTexels) {
    const std::optional<uint32_t> level = levelForReceiver(config, lsCamera, lsPosition, wsFootprint, marginTexels);
    if (!level) return;  // outside the clipmap
    // Its own level, and kVirtualPageFallbackLevels coarser: what serves it when its page overflows the pool.
    const uint32_t fallback = std::min(*level + gpu_data::kVirtualPageFallbackLevels, config.levelCount - 1);
    const uint32_t levels[2] = {*level, fallback};
    for (uint32_t marked : std::span(levels, fallback == *level ? 1 : 2)) {
        const ClipmapLevel placed = placeClipmapLevel(config, marked, lsCamera);
        PageRect pages = receiverPages(placed, lsPosition, marginTexels);
        pages.min = glm::max(pages.min, placed.window.min);  // within the level's window
        pages.max = glm::min(pages.max, placed.window.max);
        for (int32_t y = pages.min.y; y <= pages.max.y; ++y)
            for (int32_t x = pages.min.x; x <= pages.max.x; ++x) requests.request(marked, pageTableSlot(placed, {x, y}));
    }
}

}  // namespace

uint32_t virtualPageRequestWords(const VirtualClipmapConfig& config) {
    const uint64_t side = pagesPerSide(config);
    return uint32_t((uint64_t(config.levelCount) * side * side + 31) / 32);
}

VirtualPageRequests::VirtualPageRequests(const VirtualClipmapConfig& config)
    : levelCount(config.levelCount), pagesPerSide(penumbra::pagesPerSide(config)),
      words(virtualPageRequestWords(config), 0u), levelPageCounts(config.levelCount, 0u) {}

VirtualPageRequests::VirtualPageRequests(const VirtualClipmapConfig& config, std::span<const uint32_t> bits)
    : VirtualPageRequests(config) {
    PENUMBRA_ASSERT(bits.size() == words.size());
    words.assign(bits.begin(), bits.end());
    const uint32_t pagesPerLevel = pagesPerSide * pagesPerSide;
    for (uint32_t bit = 0; bit < levelCount * pagesPerLevel; ++bit)
        levelPageCounts[bit / pagesPerLevel] += (words[bit / 32] >> (bit % 32)) & 1u;
}

bool VirtualPageRequests::requested(uint32_t level, const glm::uvec2& slot) const {
    const uint32_t bit = bitOf(*this, level, slot);
    return (words[bit / 32] >> (bit % 32)) & 1u;
}

void VirtualPageRequests::request(uint32_t level, const glm::uvec2& slot) {
    const uint32_t bit = bitOf(*this, level, slot);
    const uint32_t mask = 1u << (bit % 32);
    if (words[bit / 32] & mask) return;
    words[bit / 32] |= mask;
    ++levelPageCounts[level];
}

uint32_t VirtualPageRequests::pageCount() const {
    uint32_t count = 0;
    for (uint32_t word : words) count += uint32_t(std::popcount(word));
    return count;
}

float wsFootprintPerDepth(const CameraView& view) {
    return 2.0f * std::tan(0.5f * view.yfov) / float(view.height);
}

float wsPixelFootprint(const CameraView& view, float vsDepth) { return vsDepth * wsFootprintPerDepth(view); }

glm::vec2 lsClipmapCentre(const glm::mat4& lightRotation, const CameraView& view) {
    return glm::vec2(lightRotation * glm::vec4(view.wsPosition, 1.0f));
}

VirtualPageRequests markVirtualPages(const VirtualClipmapConfig& config, const glm::mat4& lightRotation,
                                     const CameraView& view, const Image& depth, float marginTexels) {
    PENUMBRA_ASSERT(depth.width == view.width && depth.height == view.height && depth.channels == 4);
    const glm::vec2 lsCamera = lsClipmapCentre(lightRotation, view);
    VirtualPageRequests requests(config);
    forEachSurfacePixel(depth, view, [&](const glm::vec3& wsPosition, float vsDepth) {
        const glm::vec2 lsPosition(lightRotation * glm::vec4(wsPosition, 1.0f));
        markReceiver(requests, config, lsCamera, lsPosition, wsPixelFootprint(view, vsDepth), marginTexels);
    });
    return requests;
}

}  // namespace penumbra
