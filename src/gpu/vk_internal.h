#pragma once
// Internal to src/gpu/: the Vulkan side of the Device. Nothing outside src/gpu/ includes this.
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/error.h"
#include "gpu/device.h"

namespace penumbra::gpu {

const char* vkResultName(VkResult result);

// Always-on check: names the call and the VkResult in a one-line error.
#define VK_CHECK(call)                                                                                 \
    do {                                                                                               \
        const VkResult vkCheckResult_ = (call);                                                        \
        if (vkCheckResult_ != VK_SUCCESS)                                                              \
            throw ::penumbra::Error(std::string("Vulkan call failed: ") + #call + " returned " +      \
                                    ::penumbra::gpu::vkResultName(vkCheckResult_));                   \
    } while (0)

struct BufferResource {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
};

struct TextureResource {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    TextureDesc desc;
    VkFormat format = VK_FORMAT_UNDEFINED;
};

struct PipelineResource {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout pushSetLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    std::vector<BindingDesc> bindings;
};

struct TextureTableResource {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    uint32_t count = 0;
};

struct Device::Impl {
    DeviceOptions options;
    DeviceInfo info;
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkQueryPool timestampPool = VK_NULL_HANDLE;
    uint32_t timestampCapacity = 128;
    bool timestampsSupported = false;
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

    std::vector<BufferResource> buffers{1};   // index 0 = invalid handle
    std::vector<TextureResource> textures{1};
    std::vector<VkSampler> samplers{VK_NULL_HANDLE};
    std::vector<PipelineResource> pipelines{1};
    std::vector<TextureTableResource> tables{1};
    std::vector<PassTiming> timings;

    mutable std::mutex messagesMutex;
    std::vector<std::string> validationMessages;

    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
    VkDeviceMemory allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags);
    // Records and runs a one-off command buffer (uploads, readbacks).
    template <typename Record>
    void immediate(Record&& record);
    VkCommandBuffer beginImmediate();
    void endImmediate(VkCommandBuffer commandBuffer);
    VkShaderModule loadShader(const std::string& name);
};

template <typename Record>
void Device::Impl::immediate(Record&& record) {
    VkCommandBuffer commandBuffer = beginImmediate();
    record(commandBuffer);
    endImmediate(commandBuffer);
}

VkFormat toVkFormat(Format format);
VkCompareOp toVkCompareOp(CompareOp op);
bool isDepthFormat(Format format);
uint32_t bytesPerPixel(Format format);
void recordTransition(VkCommandBuffer commandBuffer, const TextureResource& texture, TextureState from, TextureState to);

}  // namespace penumbra::gpu
