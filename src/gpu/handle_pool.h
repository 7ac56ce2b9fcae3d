#pragma once
// Slots for the Device's objects, addressed by the ids inside gpu handles. A removed slot goes on a
// free list and the next insert reuses it, so a renderer that makes and frees objects frame after
// frame keeps the pool's size flat. No Vulkan.
//
// An id is a slot index (low kIndexBits bits) plus the slot's generation (the bits above). Removing
// an object bumps its slot's generation, so a handle kept past its object's destruction no longer
// matches the slot even once the slot holds a new object: using it is a PENUMBRA_ASSERT failure in
// builds with assertions and a penumbra::Error elsewhere, never a silent use of the new object. Slot 0
// is never handed out, so id 0 (the invalid handle) never names an object, whatever its generation.
// Generations wrap after kGenerations removals of one slot: only a handle that many reuses stale
// aliases again (the same trade as any fixed-width generation counter).
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace penumbra::gpu {

template <typename T>
class HandlePool {
public:
    static constexpr uint32_t kIndexBits = 20;
    static constexpr uint32_t kIndexMask = (1u << kIndexBits) - 1;
    static constexpr uint32_t kGenerations = 1u << (32 - kIndexBits);
    static constexpr uint32_t kMaxSlots = kIndexMask;  // slots 1..kIndexMask

    HandlePool() : slots_(1) {}

    uint32_t insert(T item) {
        uint32_t index = 0;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            if (slots_.size() > kMaxSlots)
                throw Error("internal: more than " + std::to_string(kMaxSlots) + " gpu objects of one kind alive");
            index = uint32_t(slots_.size());
            slots_.emplace_back();
        }
        Slot& slot = slots_[index];
        slot.item = std::move(item);
        slot.used = true;
        ++live_;
        return idOf(index, slot.generation);
    }

    // Frees the slot, bumps its generation (every handle to it is stale from now on) and returns what
    // it held.
    T remove(uint32_t id) {
        Slot& slot = live(id);
        T item = std::move(slot.item);
        slot.item = T{};
        slot.used = false;
        slot.generation = (slot.generation + 1) % kGenerations;
        free_.push_back(id & kIndexMask);
        --live_;
        return item;
    }

    bool contains(uint32_t id) const {
        const uint32_t index = id & kIndexMask;
        return index != 0 && index < slots_.size() && slots_[index].used &&
               slots_[index].generation == id >> kIndexBits;
    }
    T& at(uint32_t id) { return live(id).item; }
    const T& at(uint32_t id) const { return const_cast<HandlePool*>(this)->at(id); }

    uint32_t liveCount() const { return live_; }
    uint32_t slotCount() const { return uint32_t(slots_.size() - 1); }

    // visit(id, item) for every live object, with the id its handle holds.
    template <typename Visit>
    void forEachLive(Visit&& visit) {
        for (uint32_t index = 1; index < slots_.size(); ++index)
            if (slots_[index].used) visit(idOf(index, slots_[index].generation), slots_[index].item);
    }

private:
    struct Slot {
        T item{};
        uint32_t generation = 0;
        bool used = false;
    };

    static uint32_t idOf(uint32_t index, uint32_t generation) { return generation << kIndexBits | index; }

    // The slot a live id names; a stale, never-issued or zero id is a programming error.
    Slot& live(uint32_t id) {
        if (!contains(id)) [[unlikely]] {
            PENUMBRA_ASSERT(!"gpu handle is stale or was never issued");
            throw Error(describeDead(id));
        }
        return slots_[id & kIndexMask];
    }

    std::string describeDead(uint32_t id) const {
        const uint32_t index = id & kIndexMask, generation = id >> kIndexBits;
        std::string what = "internal: gpu handle " + std::to_string(id) + " (slot " + std::to_string(index) +
                           ", generation " + std::to_string(generation) + ") is ";
        if (index == 0 || index >= slots_.size()) return what + "not a handle this device issued";
        if (slots_[index].generation != generation)
            return what + "stale: its object was destroyed (the slot is at generation " +
                   std::to_string(slots_[index].generation) + ")";
        return what + "stale: its object was destroyed";
    }

    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
    uint32_t live_ = 0;
};

}  // namespace penumbra::gpu
