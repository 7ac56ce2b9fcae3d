#pragma once
// The caller's side of the embedding tests (penumbra/vulkan.h): an instance with validation (a message
// fails the test), lavapipe (or PENUMBRA_DEVICE=gpu's GPU), a device with what penumbra/vulkan.h lists
// (and timelineSemaphore, for ShadowSystem), one queue, images and a host readback.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "penumbra/vulkan.h"

namespace penumbra::test {

#define CHECK_VK(call) ASSERT_EQ((call), VK_SUCCESS) << #call

inline VKAPI_ATTR VkBool32 VKAPI_CALL countMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    ++*static_cast<int*>(user);
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

// The caller's side: an instance with validation, lavapipe (or PENUMBRA_DEVICE=gpu's GPU), a device
// with what penumbra/vulkan.h lists, one queue, and a target image with its memory.
class CallerVulkan : public ::testing::Test {
protected:
    void SetUp() override {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_3;
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        instanceInfo.pApplicationInfo = &app;
        instanceInfo.enabledLayerCount = 1;
        instanceInfo.ppEnabledLayerNames = &layer;
        instanceInfo.enabledExtensionCount = 1;
        instanceInfo.ppEnabledExtensionNames = &debugUtils;
        CHECK_VK(vkCreateInstance(&instanceInfo, nullptr, &instance));
        VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        messengerInfo.messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
        messengerInfo.pfnUserCallback = countMessage;
        messengerInfo.pUserData = &messages;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        CHECK_VK(create(instance, &messengerInfo, nullptr, &messenger));

        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        const char* choice = std::getenv("PENUMBRA_DEVICE");
        const bool wantCpu = !choice || std::strcmp(choice, "gpu") != 0;
        for (VkPhysicalDevice candidate : devices) {
            VkPhysicalDeviceProperties properties;
            vkGetPhysicalDeviceProperties(candidate, &properties);
            if ((properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) == wantCpu) physicalDevice = candidate;
        }
        ASSERT_NE(physicalDevice, VK_NULL_HANDLE);

        VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        features13.dynamicRendering = features13.synchronization2 = features13.maintenance4 = VK_TRUE;
        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.pNext = &features13;
        features12.drawIndirectCount = VK_TRUE;
        features12.timelineSemaphore = VK_TRUE;  // ShadowSystem's frames complete on a timeline value
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &features12;
        features.features.depthClamp = VK_TRUE;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = 0;  // graphics + compute on lavapipe and NVIDIA
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;
        uint32_t extensionCount = 0;
        const char* const* extensions = requiredVulkanDeviceExtensions(&extensionCount);
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        deviceInfo.pNext = &features;
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        deviceInfo.enabledExtensionCount = extensionCount;
        deviceInfo.ppEnabledExtensionNames = extensions;
        CHECK_VK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
        vkGetDeviceQueue(device, 0, 0, &queue);
    }

    void TearDown() override {
        if (device) {
            vkDeviceWaitIdle(device);
            for (auto [buffer, memory] : buffers) {
                vkDestroyBuffer(device, buffer, nullptr);
                vkFreeMemory(device, memory, nullptr);
            }
            for (auto [image, memory] : images) {
                vkDestroyImage(device, image, nullptr);
                vkFreeMemory(device, memory, nullptr);
            }
            if (readback) vkDestroyBuffer(device, readback, nullptr);
            if (readbackMemory) vkFreeMemory(device, readbackMemory, nullptr);
            if (semaphore) vkDestroySemaphore(device, semaphore, nullptr);
            if (pool) vkDestroyCommandPool(device, pool, nullptr);
            vkDestroyDevice(device, nullptr);
        }
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (messenger) destroy(instance, messenger, nullptr);
        if (instance) vkDestroyInstance(instance, nullptr);
        EXPECT_EQ(messages, 0) << "Vulkan validation messages appeared";
    }

    uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) {
        VkPhysicalDeviceMemoryProperties properties;
        vkGetPhysicalDeviceMemoryProperties(physicalDevice, &properties);
        for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
        return 0;
    }

    // One layout transition of a whole image of one level and layer.
    static void imageBarrier(VkCommandBuffer commandBuffer, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                             VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                             VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
        VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        barrier.srcStageMask = srcStage;
        barrier.srcAccessMask = srcAccess;
        barrier.dstStageMask = dstStage;
        barrier.dstAccessMask = dstAccess;
        barrier.oldLayout = from;
        barrier.newLayout = to;
        barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = image;
        barrier.subresourceRange = {aspect, 0, 1, 0, 1};
        VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dependency.imageMemoryBarrierCount = 1;
        dependency.pImageMemoryBarriers = &barrier;
        vkCmdPipelineBarrier2(commandBuffer, &dependency);
    }

    // A host-visible buffer of the caller holding `bytes` (freed by TearDown).
    VkBuffer makeBuffer(const void* bytes, VkDeviceSize size, VkBufferUsageFlags usage) {
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = size;
        info.usage = usage;
        VkBuffer buffer = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateBuffer(device, &info, nullptr, &buffer), VK_SUCCESS);
        VkMemoryRequirements requirements;
        vkGetBufferMemoryRequirements(device, buffer, &requirements);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = requirements.size;
        alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateMemory(device, &alloc, nullptr, &memory), VK_SUCCESS);
        EXPECT_EQ(vkBindBufferMemory(device, buffer, memory, 0), VK_SUCCESS);
        void* mapped = nullptr;
        vkMapMemory(device, memory, 0, size, 0, &mapped);
        std::memcpy(mapped, bytes, size);
        vkUnmapMemory(device, memory);
        buffers.emplace_back(buffer, memory);
        return buffer;
    }

    VkImage makeImage(VkFormat format, uint32_t width, uint32_t height,
                      VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {width, height, 1};
        info.mipLevels = info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.usage = usage;
        VkImage image = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImage(device, &info, nullptr, &image), VK_SUCCESS);
        VkMemoryRequirements requirements;
        vkGetImageMemoryRequirements(device, image, &requirements);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = requirements.size;
        alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateMemory(device, &alloc, nullptr, &memory), VK_SUCCESS);
        EXPECT_EQ(vkBindImageMemory(device, image, memory, 0), VK_SUCCESS);
        images.emplace_back(image, memory);
        return image;
    }

    // The caller's own work after Penumbra's frame: waits on `wait`, copies the image (left in
    // TRANSFER_SRC_OPTIMAL by the frame) to host memory.
    std::vector<uint8_t> readImage(VkImage image, uint32_t width, uint32_t height, VkSemaphore wait) {
        const VkDeviceSize size = VkDeviceSize(width) * height * 4;
        VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bufferInfo.size = size;
        bufferInfo.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        EXPECT_EQ(vkCreateBuffer(device, &bufferInfo, nullptr, &readback), VK_SUCCESS);
        VkMemoryRequirements requirements;
        vkGetBufferMemoryRequirements(device, readback, &requirements);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = requirements.size;
        alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        EXPECT_EQ(vkAllocateMemory(device, &alloc, nullptr, &readbackMemory), VK_SUCCESS);
        EXPECT_EQ(vkBindBufferMemory(device, readback, readbackMemory, 0), VK_SUCCESS);
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        EXPECT_EQ(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), VK_SUCCESS);
        VkCommandBufferAllocateInfo cbInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cbInfo.commandPool = pool;
        cbInfo.commandBufferCount = 1;
        VkCommandBuffer cb = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateCommandBuffers(device, &cbInfo, &cb), VK_SUCCESS);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cb, &begin);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cb, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &copy);
        vkEndCommandBuffer(cb);
        const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.waitSemaphoreCount = 1;
        submit.pWaitSemaphores = &wait;
        submit.pWaitDstStageMask = &stage;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cb;
        EXPECT_EQ(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
        vkQueueWaitIdle(queue);
        std::vector<uint8_t> pixels(size);
        void* mapped = nullptr;
        vkMapMemory(device, readbackMemory, 0, size, 0, &mapped);
        std::memcpy(pixels.data(), mapped, size);
        vkUnmapMemory(device, readbackMemory);
        return pixels;
    }

    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::vector<std::pair<VkImage, VkDeviceMemory>> images;
    std::vector<std::pair<VkBuffer, VkDeviceMemory>> buffers;
    VkBuffer readback = VK_NULL_HANDLE;
    VkDeviceMemory readbackMemory = VK_NULL_HANDLE;
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    int messages = 0;
};

}  // namespace penumbra::test
