#pragma once
// Suballocation of one linear range [0, capacity): first fit with alignment, neighbours merged on
// free. The memory allocator runs one per VkDeviceMemory block; no Vulkan here, so it is unit-tested
// on the CPU (as Filament's AtlasAllocator is).
#include <cstdint>
#include <map>
#include <optional>

namespace penumbra::gpu {

class OffsetAllocator {
public:
    explicit OffsetAllocator(uint64_t capacity);

    // Offset of `size` bytes aligned to `alignment` (a power of two), or nullopt when no free range fits.
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
    // Frees the range that allocate() returned at `offset`.
    void free(uint64_t offset);

    uint64_t capacity() const { return capacity_; }
    uint64_t usedBytes() const { return used_; }
    uint32_t allocationCount() const { return uint32_t(allocations_.size()); }
    uint32_t freeRangeCount() const { return uint32_t(freeRanges_.size()); }
    bool empty() const { return allocations_.empty(); }

private:
    void insertFree(uint64_t offset, uint64_t size);

    uint64_t capacity_ = 0;
    uint64_t used_ = 0;
    std::map<uint64_t, uint64_t> freeRanges_;  // offset -> size, disjoint and never adjacent
    // offset returned -> (start of the range taken incl. alignment padding, its size)
    std::map<uint64_t, std::pair<uint64_t, uint64_t>> allocations_;
};

}  // namespace penumbra::gpu
