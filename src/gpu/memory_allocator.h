#pragma once
// Device memory in large blocks: each request is suballocated (OffsetAllocator) from a block of its
// memory type, so a scene of thousands of buffers and textures makes a handful of vkAllocateMemory
// calls. Buffers and optimal-tiling images live in separate blocks, so bufferImageGranularity never
// matters. Requests over half a block get a dedicated allocation. Host-visible blocks stay mapped.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/offset_allocator.h"

namespace penumbra::gpu {

struct MemoryAllocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host-visible memory: the pointer at `offset`
    int32_t block = -1;      // index into the allocator's blocks; -1 = none
};

class MemoryAllocator {
public:
    static constexpr VkDeviceSize kDefaultBlockSize = 64ull << 20;

    MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties,
                    VkDeviceSize blockSize = kDefaultBlockSize);
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    // `linear`: a buffer (true) or an optimal-tiling image (false). Throws Error when out of memory.
    MemoryAllocation allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags, bool linear,
                              const std::string& name);
    void free(MemoryAllocation& allocation);
    // Gives back every block that holds nothing (free() keeps one empty block of each kind).
    void releaseEmptyBlocks();

    uint32_t blockCount() const;
    VkDeviceSize blockBytes() const;
    VkDeviceSize usedBytes() const;
    uint64_t allocationCalls() const { return allocationCalls_; }
    // Test-only (DeviceFaultInjection::failAllocation): the Nth allocate() fails as out of device
    // memory, as if its vkAllocateMemory had.
    void failRequestAt(uint64_t request) { failRequestAt_ = request; }
    // Test-only (DeviceFaultInjection::garbageByte): every host-visible allocation starts as `byte`
    // repeated (0 = untouched).
    void fillNewAllocations(uint8_t byte) { garbageByte_ = byte; }
    // Called with every new VkDeviceMemory (for debug names).
    void setOnNewMemory(void (*callback)(void* user, VkDeviceMemory memory, const std::string& name), void* user) {
        onNewMemory_ = callback;
        onNewMemoryUser_ = user;
    }

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkDeviceSize size = 0;
        uint32_t memoryType = 0;
        bool linear = true;
        bool dedicated = false;
        std::unique_ptr<OffsetAllocator> ranges;  // null for dedicated allocations
        uint8_t* mapped = nullptr;
    };
    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
    int32_t newBlock(uint32_t memoryType, VkDeviceSize size, bool linear, bool dedicated, const std::string& name);
    void releaseBlock(int32_t index);
    MemoryAllocation filled(MemoryAllocation allocation) const;
    [[noreturn]] static void throwOutOfMemory(VkDeviceSize size, const std::string& name, VkResult result);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_;
    VkDeviceSize blockSize_;
    std::vector<Block> blocks_;  // released blocks keep memory == VK_NULL_HANDLE
    uint64_t allocationCalls_ = 0;
    uint64_t requests_ = 0;
    uint64_t failRequestAt_ = 0;
    uint8_t garbageByte_ = 0;
    void (*onNewMemory_)(void*, VkDeviceMemory, const std::string&) = nullptr;
    void* onNewMemoryUser_ = nullptr;
};

}  // namespace penumbra::gpu
