#include "gpu/offset_allocator.h"

#include "core/error.h"

namespace penumbra::gpu {

OffsetAllocator::OffsetAllocator(uint64_t capacity) : capacity_(capacity) {
    if (capacity > 0) freeRanges_[0] = capacity;
}

std::optional<uint64_t> OffsetAllocator::allocate(uint64_t size, uint64_t alignment) {
    PENUMBRA_ASSERT(alignment > 0 && (alignment & (alignment - 1)) == 0);
    if (size == 0) size = 1;
    for (auto it = freeRanges_.begin(); it != freeRanges_.end(); ++it) {
        const uint64_t start = it->first, rangeSize = it->second;
        const uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
        if (aligned + size > start + rangeSize) continue;
        // Take [start, aligned + size); the padding before `aligned` belongs to this allocation, so
        // freeing it gives the whole range back.
        const uint64_t taken = aligned + size - start;
        freeRanges_.erase(it);
        if (rangeSize > taken) freeRanges_[start + taken] = rangeSize - taken;
        allocations_[aligned] = {start, taken};
        used_ += taken;
        return aligned;
    }
    return std::nullopt;
}

void OffsetAllocator::free(uint64_t offset) {
    const auto found = allocations_.find(offset);
    if (found == allocations_.end()) throw Error("internal: freeing an offset that was not allocated");
    const auto [start, size] = found->second;
    allocations_.erase(found);
    used_ -= size;
    insertFree(start, size);
}

void OffsetAllocator::insertFree(uint64_t offset, uint64_t size) {
    auto next = freeRanges_.lower_bound(offset);
    if (next != freeRanges_.end() && offset + size == next->first) {  // merge with the range after
        size += next->second;
        next = freeRanges_.erase(next);
    }
    if (next != freeRanges_.begin()) {  // merge with the range before
        auto previous = std::prev(next);
        if (previous->first + previous->second == offset) {
            previous->second += size;
            return;
        }
    }
    freeRanges_[offset] = size;
}

}  // namespace penumbra::gpu
