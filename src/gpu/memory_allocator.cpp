#include "gpu/memory_allocator.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"

namespace penumbra::gpu {

const char* vkResultName(VkResult result);

MemoryAllocator::MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties,
                                 VkDeviceSize blockSize)
    : device_(device), properties_(properties), blockSize_(blockSize) {}

MemoryAllocator::~MemoryAllocator() {
    for (Block& block : blocks_)
        if (block.memory) vkFreeMemory(device_, block.memory, nullptr);
}

uint32_t MemoryAllocator::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (properties_.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw Error("GPU memory: no memory type with the required properties");
}

int32_t MemoryAllocator::newBlock(uint32_t memoryType, VkDeviceSize size, bool linear, bool dedicated,
                                  const std::string& name) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = memoryType;
    Block block;
    block.size = size;
    block.memoryType = memoryType;
    block.linear = linear;
    block.dedicated = dedicated;
    ++allocationCalls_;
    const VkResult result = vkAllocateMemory(device_, &info, nullptr, &block.memory);
    if (result != VK_SUCCESS) throwOutOfMemory(size, name, result);
    if (properties_.memoryTypes[memoryType].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        void* mapped = nullptr;
        const VkResult mapResult = vkMapMemory(device_, block.memory, 0, VK_WHOLE_SIZE, 0, &mapped);
        if (mapResult != VK_SUCCESS) {
            vkFreeMemory(device_, block.memory, nullptr);
            throw Error(std::string("GPU memory: vkMapMemory returned ") + vkResultName(mapResult));
        }
        block.mapped = static_cast<uint8_t*>(mapped);
    }
    if (!dedicated) block.ranges = std::make_unique<OffsetAllocator>(size);
    if (onNewMemory_) onNewMemory_(onNewMemoryUser_, block.memory, dedicated ? name : "penumbra memory block");
    for (size_t i = 0; i < blocks_.size(); ++i) {
        if (!blocks_[i].memory) {
            blocks_[i] = std::move(block);
            return int32_t(i);
        }
    }
    blocks_.push_back(std::move(block));
    return int32_t(blocks_.size() - 1);
}

void MemoryAllocator::throwOutOfMemory(VkDeviceSize size, const std::string& name, VkResult result) {
    throw Error("out of GPU memory: vkAllocateMemory of " + std::to_string((size + (1 << 20) - 1) >> 20) + " MiB for " +
                (name.empty() ? std::string("an unnamed object") : name) + " returned " + vkResultName(result));
}

MemoryAllocation MemoryAllocator::allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags,
                                           bool linear, const std::string& name) {
    // Fault injection fails a request, whether or not it would have needed a new block, so that every
    // object's creation can be made to fail.
    if (++requests_ == failRequestAt_) throwOutOfMemory(requirements.size, name, VK_ERROR_OUT_OF_DEVICE_MEMORY);
    const uint32_t memoryType = findMemoryType(requirements.memoryTypeBits, flags);
    MemoryAllocation allocation;
    allocation.size = requirements.size;
    if (requirements.size > blockSize_ / 2) {
        allocation.block = newBlock(memoryType, requirements.size, linear, true, name);
        allocation.memory = blocks_[allocation.block].memory;
        allocation.mapped = blocks_[allocation.block].mapped;
        return filled(allocation);
    }
    auto place = [&](int32_t index) {
        Block& block = blocks_[index];
        const auto offset = block.ranges->allocate(requirements.size, std::max<VkDeviceSize>(requirements.alignment, 1));
        if (!offset) return false;
        allocation.block = index;
        allocation.memory = block.memory;
        allocation.offset = *offset;
        allocation.mapped = block.mapped ? block.mapped + *offset : nullptr;
        return true;
    };
    for (size_t i = 0; i < blocks_.size(); ++i) {
        const Block& block = blocks_[i];
        if (block.memory && !block.dedicated && block.memoryType == memoryType && block.linear == linear &&
            place(int32_t(i)))
            return filled(allocation);
    }
    if (!place(newBlock(memoryType, blockSize_, linear, false, name)))
        throw Error("internal: a fresh memory block could not hold " + std::to_string(requirements.size) + " bytes");
    return filled(allocation);
}

MemoryAllocation MemoryAllocator::filled(MemoryAllocation allocation) const {
    if (garbageByte_ && allocation.mapped) std::memset(allocation.mapped, garbageByte_, allocation.size);
    return allocation;
}

void MemoryAllocator::free(MemoryAllocation& allocation) {
    if (allocation.block < 0) return;
    Block& block = blocks_.at(allocation.block);
    if (block.dedicated) {
        releaseBlock(allocation.block);
    } else {
        block.ranges->free(allocation.offset);
        // Keep one empty block of each kind for the next request; give back any further ones.
        if (block.ranges->empty()) {
            const bool anotherEmpty = std::any_of(blocks_.begin(), blocks_.end(), [&](const Block& other) {
                return &other != &block && other.memory && !other.dedicated && other.memoryType == block.memoryType &&
                       other.linear == block.linear && other.ranges->empty();
            });
            if (anotherEmpty) releaseBlock(allocation.block);
        }
    }
    allocation = MemoryAllocation{};
}

void MemoryAllocator::releaseEmptyBlocks() {
    for (size_t i = 0; i < blocks_.size(); ++i)
        if (blocks_[i].memory && !blocks_[i].dedicated && blocks_[i].ranges->empty()) releaseBlock(int32_t(i));
}

void MemoryAllocator::releaseBlock(int32_t index) {
    Block& block = blocks_.at(index);
    vkFreeMemory(device_, block.memory, nullptr);
    block = Block{};
}

uint32_t MemoryAllocator::blockCount() const {
    return uint32_t(std::count_if(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.memory != VK_NULL_HANDLE; }));
}

VkDeviceSize MemoryAllocator::blockBytes() const {
    VkDeviceSize total = 0;
    for (const Block& block : blocks_) {
        if (!block.memory) continue;
        total += block.size;
    }
    return total;
}

VkDeviceSize MemoryAllocator::usedBytes() const {
    VkDeviceSize total = 0;
    for (const Block& block : blocks_)
        if (block.memory) total += block.dedicated ? block.size : block.ranges->usedBytes();
    return total;
}

}  // namespace penumbra::gpu
