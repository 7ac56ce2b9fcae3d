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
//             (say so with externalVulkanDevice's bufferInt64Atomics argument);
//             timelineSemaphore (1.2) for ShadowSystem (its timelineSemaphores argument);
//             shaderStorageImageExtendedFormats (1.0): virtual shadow map pools of 2 bytes a texel, not 4
//             (set the returned struct's storageImageExtendedFormats);
//   a queue whose family supports graphics and compute (Penumbra submits to it: externally
//   synchronize it with your own submissions, e.g. submit from one thread).
// The target image needs VK_IMAGE_USAGE_TRANSFER_DST_BIT and a format that is a blit destination.
#include <vulkan/vulkan.h>

#include <penumbra/device.h>
#include <penumbra/renderer.h>
#include <penumbra/shadow_system.h>

namespace penumbra {

// The device extensions Penumbra needs on a caller's VkDevice.
inline const char* const* requiredVulkanDeviceExtensions(uint32_t* count) {
    static const char* const extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    *count = 1;
    return extensions;
}

inline ExternalVulkanDevice externalVulkanDevice(VkInstance instance, VkPhysicalDevice physicalDevice, VkDevice device,
                                                 VkQueue queue, uint32_t queueFamily, bool bufferInt64Atomics = false,
                                                 bool timelineSemaphores = false) {
    ExternalVulkanDevice external;
    external.instance = reinterpret_cast<uint64_t>(instance);
    external.physicalDevice = reinterpret_cast<uint64_t>(physicalDevice);
    external.device = reinterpret_cast<uint64_t>(device);
    external.queue = reinterpret_cast<uint64_t>(queue);
    external.queueFamily = queueFamily;
    external.bufferInt64Atomics = bufferInt64Atomics;
    external.timelineSemaphores = timelineSemaphores;
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

// ---- ShadowSystem (penumbra/shadow_system.h) in Vulkan types.

inline VkDescriptorType shadowDescriptorVkType(ShadowDescriptorType type) {
    switch (type) {
        case ShadowDescriptorType::UniformBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        case ShadowDescriptorType::StorageBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        case ShadowDescriptorType::CombinedImageSampler: break;
    }
    return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
}

// The descriptor set layout of <penumbra/shadows.glsl> (kShadowDescriptors) for shaders that include it
// with PENUMBRA_SHADOW_BINDING_BASE `bindingBase`, read by `stages`. The caller owns it.
inline VkResult createShadowDescriptorSetLayout(VkDevice device, VkShaderStageFlags stages, uint32_t bindingBase,
                                                VkDescriptorSetLayout* layout) {
    VkDescriptorSetLayoutBinding bindings[kShadowBindingCount] = {};
    for (uint32_t i = 0; i < kShadowBindingCount; ++i) {
        bindings[i].binding = bindingBase + kShadowDescriptors[i].binding;
        bindings[i].descriptorType = shadowDescriptorVkType(kShadowDescriptors[i].type);
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = stages;
    }
    VkDescriptorSetLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    info.bindingCount = kShadowBindingCount;
    info.pBindings = bindings;
    return vkCreateDescriptorSetLayout(device, &info, nullptr, layout);
}

// The pool sizes one such set needs (add them to the caller's pool per set).
inline void shadowDescriptorPoolSizes(VkDescriptorPoolSize sizes[3]) {
    sizes[0] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0};
    sizes[1] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0};
    sizes[2] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0};
    for (const ShadowDescriptor& descriptor : kShadowDescriptors) ++sizes[uint32_t(descriptor.type)].descriptorCount;
}

// Writes a frame's descriptors into `set` (made with createShadowDescriptorSetLayout's layout, same
// base). The set must not be in use by the GPU: keep one per frame in flight.
inline void writeShadowDescriptors(VkDevice device, VkDescriptorSet set, const ShadowFrameBindings& frame,
                                   uint32_t bindingBase = 0) {
    VkWriteDescriptorSet writes[kShadowBindingCount] = {};
    VkDescriptorBufferInfo buffers[kShadowBindingCount] = {};
    VkDescriptorImageInfo images[kShadowBindingCount] = {};
    for (uint32_t i = 0; i < kShadowBindingCount; ++i) {
        const ShadowDescriptorResource& resource = frame.descriptors[i];
        VkWriteDescriptorSet& write = writes[i];
        write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        write.dstSet = set;
        write.dstBinding = bindingBase + resource.binding;
        write.descriptorCount = 1;
        write.descriptorType = shadowDescriptorVkType(resource.type);
        if (resource.type == ShadowDescriptorType::CombinedImageSampler) {
            images[i].sampler = reinterpret_cast<VkSampler>(resource.vkSampler);
            images[i].imageView = reinterpret_cast<VkImageView>(resource.vkImageView);
            images[i].imageLayout = VkImageLayout(resource.vkImageLayout);
            write.pImageInfo = &images[i];
        } else {
            buffers[i].buffer = reinterpret_cast<VkBuffer>(resource.vkBuffer);
            buffers[i].offset = resource.offset;
            buffers[i].range = resource.range;
            write.pBufferInfo = &buffers[i];
        }
    }
    vkUpdateDescriptorSets(device, kShadowBindingCount, writes, 0, nullptr);
}

// ShadowSystem::recordFrame with a VkCommandBuffer.
// ShadowSystem::recordFrame with a VkCommandBuffer and, optionally, the engine's depth image of the view
// and its depth view (VK_FORMAT_D32_SFLOAT, in DEPTH_ATTACHMENT_OPTIMAL; penumbra/shadow_system.h,
// ShadowViewDepth).
inline ShadowFrameBindings recordShadowFrame(ShadowSystem& shadows, VkCommandBuffer commandBuffer,
                                             const Settings& settings, const CameraView& view,
                                             VkImage depth = VK_NULL_HANDLE, VkImageView depthView = VK_NULL_HANDLE) {
    ShadowViewDepth viewDepth;
    viewDepth.vkImage = reinterpret_cast<uint64_t>(depth);
    viewDepth.vkImageView = reinterpret_cast<uint64_t>(depthView);
    return shadows.recordFrame(reinterpret_cast<uint64_t>(commandBuffer), settings, view, depth ? &viewDepth : nullptr);
}

// The signal the submission of a shadow frame's command buffer carries (vkQueueSubmit2's
// pSignalSemaphoreInfos): Penumbra's timeline semaphore, to the frame's completion value.
inline VkSemaphoreSubmitInfo shadowFrameSignal(const ShadowFrameBindings& frame) {
    VkSemaphoreSubmitInfo signal{};
    signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
    signal.semaphore = reinterpret_cast<VkSemaphore>(frame.vkCompletionSemaphore);
    signal.value = frame.completionValue;
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    return signal;
}

}  // namespace penumbra
