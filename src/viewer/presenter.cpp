#include "viewer/presenter.h"

#include <cstring>

#include "penumbra/error.h"
#include "penumbra/vulkan.h"
#include "viewer/imgui_layer.h"
#include "viewer/swapchain.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

namespace {

VkFormat variantOf(VkFormat swapchainFormat, bool unorm) {
    if (swapchainFormat == VK_FORMAT_B8G8R8A8_SRGB || swapchainFormat == VK_FORMAT_B8G8R8A8_UNORM)
        return unorm ? VK_FORMAT_B8G8R8A8_UNORM : VK_FORMAT_B8G8R8A8_SRGB;
    return unorm ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R8G8B8A8_SRGB;
}

}  // namespace

void colorImageBarrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                       VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(commands, &dependency);
}

Presenter::Presenter(VulkanContext& context, Swapchain& swapchain) : context_(context), swapchain_(swapchain) {
    try {
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = context.queueFamily;
        VIEWER_VK(vkCreateCommandPool(context.device, &poolInfo, nullptr, &pool_));
        slots_.resize(kFramesInFlight);
        for (Slot& slot : slots_) {
            VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
            fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
            VIEWER_VK(vkCreateFence(context.device, &fenceInfo, nullptr, &slot.fence));
            VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            VIEWER_VK(vkCreateSemaphore(context.device, &semaphoreInfo, nullptr, &slot.acquired));
            VIEWER_VK(vkCreateSemaphore(context.device, &semaphoreInfo, nullptr, &slot.sceneRendered));
            VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
            allocInfo.commandPool = pool_;
            allocInfo.commandBufferCount = 1;
            VIEWER_VK(vkAllocateCommandBuffers(context.device, &allocInfo, &slot.commands));
        }
    } catch (...) {
        release();
        throw;
    }
}

Presenter::~Presenter() { release(); }

void Presenter::release() {
    if (context_.device) vkDeviceWaitIdle(context_.device);
    for (Slot& slot : slots_) {
        destroySceneImage(slot);
        if (slot.fence) vkDestroyFence(context_.device, slot.fence, nullptr);
        if (slot.acquired) vkDestroySemaphore(context_.device, slot.acquired, nullptr);
        if (slot.sceneRendered) vkDestroySemaphore(context_.device, slot.sceneRendered, nullptr);
    }
    slots_.clear();
    if (screenshotBuffer_) vkDestroyBuffer(context_.device, screenshotBuffer_, nullptr);
    if (screenshotMemory_) vkFreeMemory(context_.device, screenshotMemory_, nullptr);
    screenshotBuffer_ = VK_NULL_HANDLE;
    screenshotMemory_ = VK_NULL_HANDLE;
    if (pool_) vkDestroyCommandPool(context_.device, pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
}

bool Presenter::beginFrame() {
    Slot& slot = slots_[slot_];
    VIEWER_VK(vkWaitForFences(context_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX));
    const VkResult result =
        vkAcquireNextImageKHR(context_.device, swapchain_.handle(), UINT64_MAX, slot.acquired, VK_NULL_HANDLE, &image_);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (result != VK_SUBOPTIMAL_KHR) checkVk(result, "vkAcquireNextImageKHR");
    return true;
}

void Presenter::destroySceneImage(Slot& slot) {
    if (slot.sceneImage) vkDestroyImage(context_.device, slot.sceneImage, nullptr);
    if (slot.sceneMemory) vkFreeMemory(context_.device, slot.sceneMemory, nullptr);
    slot.sceneImage = VK_NULL_HANDLE;
    slot.sceneMemory = VK_NULL_HANDLE;
}

// The slot's fence was waited for, so its previous image is no longer in use.
void Presenter::makeSceneImage(Slot& slot, VkFormat format) {
    destroySceneImage(slot);
    slot.sceneImage = context_.createImage(format, swapchain_.extent(),
                                           VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &slot.sceneMemory);
    slot.sceneFormat = format;
    slot.sceneExtent = swapchain_.extent();
}

ExternalImage Presenter::sceneTarget(bool aov) {
    Slot& slot = slots_[slot_];
    const VkFormat format = variantOf(swapchain_.format(), aov);
    const VkExtent2D extent = swapchain_.extent();
    if (!slot.sceneImage || slot.sceneFormat != format || slot.sceneExtent.width != extent.width ||
        slot.sceneExtent.height != extent.height)
        makeSceneImage(slot, format);
    return externalImage(slot.sceneImage, format, extent, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_NULL_HANDLE, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.sceneRendered);
}

void Presenter::recordScreenshotCopy(VkCommandBuffer commands, VkImage image) {
    const VkExtent2D extent = swapchain_.extent();
    const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (bytes != screenshotBytes_) {
        if (screenshotBuffer_) vkDestroyBuffer(context_.device, screenshotBuffer_, nullptr);
        if (screenshotMemory_) vkFreeMemory(context_.device, screenshotMemory_, nullptr);
        screenshotBuffer_ = VK_NULL_HANDLE;
        screenshotMemory_ = VK_NULL_HANDLE;
        screenshotBytes_ = 0;
        screenshotBuffer_ = context_.createHostBuffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &screenshotMemory_);
        screenshotBytes_ = bytes;
    }
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(commands, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, screenshotBuffer_, 1, &copy);
    VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = screenshotBuffer_;
    barrier.size = VK_WHOLE_SIZE;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(commands, &dependency);
}

Image Presenter::readScreenshot() {
    const VkExtent2D extent = swapchain_.extent();
    Image image;
    image.width = extent.width;
    image.height = extent.height;
    image.channels = 3;
    image.pixels.resize(size_t(extent.width) * extent.height * 3);
    void* mapped = nullptr;
    VIEWER_VK(vkMapMemory(context_.device, screenshotMemory_, 0, screenshotBytes_, 0, &mapped));
    const auto* bgra = static_cast<const uint8_t*>(mapped);
    const bool blueFirst = swapchain_.format() == VK_FORMAT_B8G8R8A8_SRGB;
    for (size_t p = 0; p < size_t(extent.width) * extent.height; ++p)
        for (int c = 0; c < 3; ++c) image.pixels[p * 3 + c] = bgra[p * 4 + (blueFirst ? 2 - c : c)];
    vkUnmapMemory(context_.device, screenshotMemory_);
    return image;
}

bool Presenter::endFrame(ImGuiLayer& imgui, const OverlayRecorder& overlay, Image* screenshot) {
    Slot& slot = slots_[slot_];
    const VkImage target = swapchain_.images().at(image_);
    const VkExtent2D extent = swapchain_.extent();
    VkCommandBuffer commands = slot.commands;
    VIEWER_VK(vkResetCommandBuffer(commands, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VIEWER_VK(vkBeginCommandBuffer(commands, &begin));
    colorImageBarrier(commands, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    // Byte for byte: the scene image's format differs from the swapchain's in the sRGB flag at most.
    VkImageCopy copy{};
    copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.extent = {extent.width, extent.height, 1};
    vkCmdCopyImage(commands, slot.sceneImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    if (overlay) overlay(commands, target, extent);
    imgui.record(commands, image_, extent);
    if (screenshot) recordScreenshotCopy(commands, target);
    colorImageBarrier(commands, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                      VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                      VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, 0);
    VIEWER_VK(vkEndCommandBuffer(commands));

    const VkSemaphore waits[] = {slot.acquired, slot.sceneRendered};
    const VkPipelineStageFlags waitStages[] = {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT};
    const VkSemaphore rendered = swapchain_.renderedSemaphore(image_);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 2;
    submit.pWaitSemaphores = waits;
    submit.pWaitDstStageMask = waitStages;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &rendered;
    VIEWER_VK(vkResetFences(context_.device, 1, &slot.fence));
    VIEWER_VK(vkQueueSubmit(context_.queue, 1, &submit, slot.fence));
    if (screenshot) {
        VIEWER_VK(vkWaitForFences(context_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX));
        *screenshot = readScreenshot();
    }

    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered;
    const VkSwapchainKHR swapchain = swapchain_.handle();
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &image_;
    const VkResult result = vkQueuePresentKHR(context_.queue, &present);
    slot_ = (slot_ + 1) % kFramesInFlight;
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) return false;
    checkVk(result, "vkQueuePresentKHR");
    return true;
}

}  // namespace penumbra::viewer
