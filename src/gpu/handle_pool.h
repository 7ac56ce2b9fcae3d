#pragma once
// Slots for the Device's objects, addressed by the ids inside gpu handles. A removed slot goes on a
// free list and the next insert reuses it, so a renderer that makes and frees objects frame after
// frame keeps the pool's size flat. Id 0 is never handed out (it is the invalid handle). No Vulkan.
#include <cstdint>
#include <vector>

#include "core/error.h"

namespace penumbra::gpu {

template <typename T>
class HandlePool {
public:
    HandlePool() : items_(1), used_(1, false) {}

    uint32_t insert(T item) {
        uint32_t id = 0;
        if (!free_.empty()) {
            id = free_.back();
            free_.pop_back();
            items_[id] = std::move(item);
            used_[id] = true;
        } else {
            id = uint32_t(items_.size());
            items_.push_back(std::move(item));
            used_.push_back(true);
        }
        ++live_;
        return id;
    }

    // Frees the slot and returns what it held.
    T remove(uint32_t id) {
        PENUMBRA_ASSERT(contains(id));
        T item = std::move(items_[id]);
        items_[id] = T{};
        used_[id] = false;
        free_.push_back(id);
        --live_;
        return item;
    }

    bool contains(uint32_t id) const { return id != 0 && id < items_.size() && used_[id]; }
    T& at(uint32_t id) {
        if (!contains(id)) throw Error("internal: gpu handle " + std::to_string(id) + " is not alive");
        return items_[id];
    }
    const T& at(uint32_t id) const { return const_cast<HandlePool*>(this)->at(id); }

    uint32_t liveCount() const { return live_; }
    uint32_t slotCount() const { return uint32_t(items_.size() - 1); }

    template <typename Visit>
    void forEachLive(Visit&& visit) {
        for (uint32_t id = 1; id < items_.size(); ++id)
            if (used_[id]) visit(id, items_[id]);
    }

private:
    std::vector<T> items_;
    std::vector<bool> used_;
    std::vector<uint32_t> free_;
    uint32_t live_ = 0;
};

}  // namespace penumbra::gpu
