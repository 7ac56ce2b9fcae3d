#include "viewer/swapchain.h"

#include <algorithm>
#include <cstdio>

#include "penumbra/error.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

namespace {

VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice physicalDevice, VkSurfaceKHR surface) {
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physicalDevice, surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physicalDevice, surface, &count, formats.data());
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
        for (const VkSurfaceFormatKHR& format : formats)
            if (format.format == wanted && format.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return format;
    throw Error("the window's surface offers no 8-bit sRGB format (B8G8R8A8_SRGB or R8G8B8A8_SRGB)");
}

VkPresentModeKHR supportedPresentMode(VkPhysicalDevice physicalDevice, VkSurfaceKHR surface, VkPresentModeKHR wanted) {
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(physicalDevice, surface, &count, nullptr);
    std::vector<VkPresentModeKHR> modes(count);
    vkGetPhysicalDeviceSurfacePresentModesKHR(physicalDevice, surface, &count, modes.data());
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
    // FIFO is the one mode every surface offers.
    std::fprintf(stderr, "penumbra-viewer: warning: the window's surface offers no mailbox present mode; presenting with fifo\n");
    return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(VulkanContext& context, VkPresentModeKHR presentMode) : context_(context) {
    format_ = chooseFormat(context.physicalDevice, context.surface);
    presentMode_ = supportedPresentMode(context.physicalDevice, context.surface, presentMode);
}

Swapchain::~Swapchain() {
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(context_.device, swapchain_, nullptr);
}

void Swapchain::destroyImages() {
    for (VkImageView view : views_) vkDestroyImageView(context_.device, view, nullptr);
    for (VkSemaphore semaphore : rendered_) vkDestroySemaphore(context_.device, semaphore, nullptr);
    views_.clear();
    rendered_.clear();
    images_.clear();
}

void Swapchain::recreate(uint32_t width, uint32_t height) {
    VIEWER_VK(vkDeviceWaitIdle(context_.device));
    VkSurfaceCapabilitiesKHR capabilities;
    VIEWER_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice, context_.surface, &capabilities));
    extent_ = capabilities.currentExtent;
    if (extent_.width == UINT32_MAX) {
        extent_.width = std::clamp(width, capabilities.minImageExtent.width, capabilities.maxImageExtent.width);
        extent_.height = std::clamp(height, capabilities.minImageExtent.height, capabilities.maxImageExtent.height);
    }
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((capabilities.supportedUsageFlags & usage) != usage)
        throw Error("the window's swapchain cannot be a transfer source and destination");
    uint32_t imageCount = capabilities.minImageCount + 1;
    if (capabilities.maxImageCount > 0) imageCount = std::min(imageCount, capabilities.maxImageCount);
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = context_.surface;
    info.minImageCount = imageCount;
    info.imageFormat = format_.format;
    info.imageColorSpace = format_.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = capabilities.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = presentMode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VIEWER_VK(vkCreateSwapchainKHR(context_.device, &info, nullptr, &created));
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(context_.device, swapchain_, nullptr);
    swapchain_ = created;

    uint32_t count = 0;
    VIEWER_VK(vkGetSwapchainImagesKHR(context_.device, swapchain_, &count, nullptr));
    images_.resize(count);
    VIEWER_VK(vkGetSwapchainImagesKHR(context_.device, swapchain_, &count, images_.data()));
    for (VkImage image : images_) {
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format_.format;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VIEWER_VK(vkCreateImageView(context_.device, &viewInfo, nullptr, &views_.emplace_back()));
        VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VIEWER_VK(vkCreateSemaphore(context_.device, &semaphoreInfo, nullptr, &rendered_.emplace_back()));
    }
}

}  // namespace penumbra::viewer
