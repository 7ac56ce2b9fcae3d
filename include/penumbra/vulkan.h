#pragma once
// Embedding Penumbra in a Vulkan program: a penumbra::Device on the caller's VkDevice, and frames
// rendered into the caller's VkImage. Everything here is inline over the Vulkan-free API of
// <penumbra/device.h> and <penumbra/renderer.h>; only this header needs <vulkan/vulkan.h>.
//
// The caller's VkDevice must be Vulkan 1.3 with these enabled:
//   features: dynamicRendering, synchronization2, maintenance4 (1.3), drawIndirectCount (1.2),
//             depthClamp (1.0);
//   extension: VK_KHR_push_descriptor;
//   optional: shaderInt64 (1.0) + shaderBufferInt64Atomics (1.2) for the visibility-buffer main view
//             (say so with externalVulkanDevice's last argument);
//   a queue whose family supports graphics and compute (Penumbra submits to it: externally
//   synchronize it with your own submissions, e.g. submit from one thread).
// The target image needs VK_IMAGE_USAGE_TRANSFER_DST_BIT and a format that is a blit destination.
#include <vulkan/vulkan.h>

#include <penumbra/device.h>
#include <penumbra/renderer.h>

namespace penumbra {

// The device extensions Penumbra needs on a caller's VkDevice.
inline const char* const* requiredVulkanDeviceExtensions(uint32_t* count) {
    static const char* const extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    *count = 1;
    return extensions;
}

inline ExternalVulkanDevice externalVulkanDevice(VkInstance instance, VkPhysicalDevice physicalDevice, VkDevice device,
                                                 VkQueue queue, uint32_t queueFamily, bool bufferInt64Atomics = false) {
    ExternalVulkanDevice external;
    external.instance = reinterpret_cast<uint64_t>(instance);
    external.physicalDevice = reinterpret_cast<uint64_t>(physicalDevice);
    external.device = reinterpret_cast<uint64_t>(device);
    external.queue = reinterpret_cast<uint64_t>(queue);
    external.queueFamily = queueFamily;
    external.bufferInt64Atomics = bufferInt64Atomics;
    return external;
}

// A frame's target: the image is in `initialLayout` when the frame starts (UNDEFINED discards its
// contents) and is left in `finalLayout` (e.g. PRESENT_SRC_KHR for a swapchain image). The frame
// waits on `wait` (at `waitStages`) before writing and signals `signal` when done; both optional.
inline ExternalImage externalImage(VkImage image, VkFormat format, VkExtent2D extent, VkImageLayout initialLayout,
                                   VkImageLayout finalLayout, VkSemaphore wait = VK_NULL_HANDLE,
                                   VkPipelineStageFlags2 waitStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                   VkSemaphore signal = VK_NULL_HANDLE) {
    ExternalImage target;
    target.vkImage = reinterpret_cast<uint64_t>(image);
    target.vkFormat = uint32_t(format);
    target.width = extent.width;
    target.height = extent.height;
    target.vkInitialLayout = uint32_t(initialLayout);
    target.vkFinalLayout = uint32_t(finalLayout);
    target.vkWaitSemaphore = reinterpret_cast<uint64_t>(wait);
    target.vkWaitStageMask = uint64_t(waitStages);
    target.vkSignalSemaphore = reinterpret_cast<uint64_t>(signal);
    return target;
}

}  // namespace penumbra
