#pragma once
// The viewer's own Vulkan objects: an instance with the window system's extensions (and, on
// request, the validation layer whose messages are counted), a surface for the GLFW window, and a
// device with what <penumbra/vulkan.h> asks for, on which a penumbra::Device is built.
#include <atomic>
#include <string>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace penumbra::viewer {

// Names the Vulkan call and its VkResult in a penumbra::Error.
void checkVk(VkResult result, const char* call);
#define VIEWER_VK(call) ::penumbra::viewer::checkVk((call), #call)

class VulkanContext {
public:
    // `deviceChoice`: auto | gpu | cpu | N (N counts the devices that can render and present, in the
    // loader's order). Throws penumbra::Error with one line when none fits.
    VulkanContext(GLFWwindow* window, const std::string& deviceChoice, bool validation);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    bool bufferInt64Atomics = false;  // enabled on the device (the visibility-buffer main view)
    std::string deviceName;

    uint32_t validationMessages() const { return messages_.load(); }
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
    // A 2D colour image with its own device-local memory, and a host-visible coherent buffer.
    VkImage createImage(VkFormat format, VkExtent2D extent, VkImageUsageFlags usage, VkDeviceMemory* memory) const;
    VkBuffer createHostBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkDeviceMemory* memory) const;

private:
    void createInstance(bool validation);
    void chooseDevice(const std::string& choice);
    void createDevice();
    void release();

    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::atomic<uint32_t> messages_{0};
};

}  // namespace penumbra::viewer
