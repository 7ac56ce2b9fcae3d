#include "shadows/virtual_page_pool.h"

#include <algorithm>
#include <unordered_set>
#include <utility>

#include "core/error.h"

namespace penumbra {

VirtualPageTableLayout clipmapTableLayout(const VirtualClipmapConfig& config) {
    return {pagesPerSide(config), config.levelCount, 1, false};
}

size_t VirtualPageKeyHash::operator()(const VirtualPageKey& key) const {
    uint64_t h = (uint64_t(key.map) << 40) ^ (uint64_t(uint32_t(key.page.x)) << 20) ^ uint64_t(uint32_t(key.page.y));
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    return size_t(h);
}

VirtualPagePool::VirtualPagePool(uint32_t capacity, uint32_t keepFrames) : capacity_(capacity), keepFrames_(keepFrames) {
    free_.reserve(capacity);
    for (uint32_t i = capacity; i > 0; --i) free_.push_back(i - 1);  // page 0 is handed out first
}

VirtualPageFrame VirtualPagePool::update(std::span<const VirtualPageKey> requests) {
    ++frame_;
    VirtualPageFrame frame;
    frame.evicted = std::exchange(releasedSinceUpdate_, 0u);
    // Resident requests first, so that no page this frame requests is taken for another, nor freed
    // as idle: a page requested again after exactly keepFrames idle frames stays cached.
    std::vector<VirtualPageKey> missing;
    std::unordered_set<VirtualPageKey, VirtualPageKeyHash> seen;
    for (const VirtualPageKey& key : requests) {
        if (!seen.insert(key).second) continue;
        ++frame.requested;
        const auto found = pages_.find(key);
        if (found == pages_.end()) {
            missing.push_back(key);
            continue;
        }
        found->second.lastRequested = frame_;
        ++frame.cached;
        frame.toDraw += found->second.dirty ? 1u : 0u;
    }
    freeIdlePages(frame);
    for (const VirtualPageKey& key : missing) {
        if (allocate(key, frame)) {
            ++frame.allocated;
            ++frame.toDraw;
        } else {
            ++frame.overflowed;
        }
    }
    frame.resident = residentCount();
    return frame;
}

uint32_t VirtualPagePool::releaseOutside(uint32_t map, const PageRect& window) {
    uint32_t released = 0;
    for (auto it = pages_.begin(); it != pages_.end();) {
        if (it->first.map == map && !window.contains({it->first.page, it->first.page})) {
            free_.push_back(it->second.physical);
            it = pages_.erase(it);
            ++released;
        } else {
            ++it;
        }
    }
    releasedSinceUpdate_ += released;
    return released;
}

std::vector<VirtualPageKey> VirtualPagePool::residentPages() const {
    std::vector<VirtualPageKey> keys;
    keys.reserve(pages_.size());
    for (const auto& [key, entry] : pages_) keys.push_back(key);
    return keys;
}

// A free physical page, or the one of the least recently requested page not requested this frame.
bool VirtualPagePool::allocate(const VirtualPageKey& key, VirtualPageFrame& frame) {
    uint32_t physical = 0;
    if (!free_.empty()) {
        physical = free_.back();
        free_.pop_back();
    } else {
        auto victim = pages_.end();
        for (auto it = pages_.begin(); it != pages_.end(); ++it)
            if (it->second.lastRequested < frame_ &&
                (victim == pages_.end() || it->second.lastRequested < victim->second.lastRequested))
                victim = it;
        if (victim == pages_.end()) return false;
        physical = victim->second.physical;
        pages_.erase(victim);
        ++frame.evicted;
    }
    pages_[key] = Entry{physical, frame_, true};
    return true;
}

void VirtualPagePool::freeIdlePages(VirtualPageFrame& frame) {
    for (auto it = pages_.begin(); it != pages_.end();) {
        if (frame_ - it->second.lastRequested > keepFrames_) {
            free_.push_back(it->second.physical);
            it = pages_.erase(it);
            ++frame.evicted;
        } else {
            ++it;
        }
    }
}

std::optional<uint32_t> VirtualPagePool::physicalPage(const VirtualPageKey& key) const {
    const auto found = pages_.find(key);
    if (found == pages_.end()) return std::nullopt;
    return found->second.physical;
}

bool VirtualPagePool::needsDraw(const VirtualPageKey& key) const {
    const auto found = pages_.find(key);
    return found != pages_.end() && found->second.dirty;
}

void VirtualPagePool::markDrawn(const VirtualPageKey& key) {
    const auto found = pages_.find(key);
    PENUMBRA_ASSERT(found != pages_.end());
    if (found != pages_.end()) found->second.dirty = false;
}

void VirtualPagePool::invalidateMap(uint32_t map) {
    for (auto& [key, entry] : pages_)
        if (key.map == map) entry.dirty = true;
}

void VirtualPagePool::invalidatePages(uint32_t map, const PageRect& pages) {
    if (pages.empty()) return;
    for (auto& [key, entry] : pages_)
        if (key.map == map && key.page.x >= pages.min.x && key.page.x <= pages.max.x && key.page.y >= pages.min.y &&
            key.page.y <= pages.max.y)
            entry.dirty = true;
}

uint32_t nextPoolPressureSteps(uint32_t steps, const VirtualPoolLoad& load) {
    if (load.overflowed > 0) return std::min(steps + 1, kMaxPoolPressureSteps);
    if (steps > 0 && uint64_t(load.requested) * 4 * 2 <= load.capacity) return steps - 1;
    return steps;
}

}  // namespace penumbra
