#pragma once
// The engine's Vulkan: instance, device and queue made the engine's way (Penumbra runs on them), and the
// few helpers its renderer needs: buffers and images with memory, one-off command buffers.
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

namespace own {

// Throws std::runtime_error naming the call when a Vulkan call fails.
void check(VkResult result, const char* call);
#define OWN_VK(call) ::own::check((call), #call)

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;  // host-visible buffers
};

struct Texture {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, mipLevels = 1;
};

class VulkanContext {
public:
    // device: "cpu" picks lavapipe, anything else a GPU. validation: the Khronos layer; a message makes
    // validationMessages() non-zero.
    VulkanContext(const std::string& device, bool validation);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    Buffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
    void destroy(Buffer& buffer);
    Texture createTexture(VkFormat format, uint32_t width, uint32_t height, uint32_t mipLevels, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect);
    void destroy(Texture& texture);
    // A command buffer recorded, submitted and waited for (uploads).
    VkCommandBuffer beginOneOff();
    void submitOneOff(VkCommandBuffer commandBuffer);

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    int validationMessages = 0;

private:
    void create(const std::string& device, bool validation);
    void release();  // every object made so far
    uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

}  // namespace own
