#include "viewer/imgui_layer.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>

#include "penumbra/error.h"
#include "viewer/swapchain.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

namespace {

void checkImGuiVk(VkResult result) { checkVk(result, "ImGui Vulkan backend"); }

VkRenderPass createRenderPass(VkDevice device, VkFormat format) {
    VkAttachmentDescription attachment{};
    attachment.format = format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference colour{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colour;
    VkSubpassDependency dependencies[2]{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VIEWER_VK(vkCreateRenderPass(device, &info, nullptr, &renderPass));
    return renderPass;
}

}  // namespace

ImGuiLayer::ImGuiLayer(VulkanContext& context, GLFWwindow* window, const Swapchain& swapchain, VkCommandPool pool)
    : context_(context) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    try {
        renderPass_ = createRenderPass(context.device, swapchain.format());
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
        VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        poolInfo.maxSets = 16;
        poolInfo.poolSizeCount = 1;
        poolInfo.pPoolSizes = sizes;
        VIEWER_VK(vkCreateDescriptorPool(context.device, &poolInfo, nullptr, &descriptorPool_));
        ImGui_ImplGlfw_InitForVulkan(window, true);
        ImGui_ImplVulkan_InitInfo info{};
        info.Instance = context.instance;
        info.PhysicalDevice = context.physicalDevice;
        info.Device = context.device;
        info.QueueFamily = context.queueFamily;
        info.Queue = context.queue;
        info.DescriptorPool = descriptorPool_;
        info.MinImageCount = 2;
        info.ImageCount = uint32_t(std::max<size_t>(2, swapchain.images().size()));
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        info.CheckVkResultFn = checkImGuiVk;
        ImGui_ImplVulkan_Init(&info, renderPass_);
        backendsReady_ = true;
        uploadFonts(pool);
        createFramebuffers(swapchain);
    } catch (...) {
        release();
        throw;
    }
}

ImGuiLayer::~ImGuiLayer() { release(); }

void ImGuiLayer::release() {
    destroyFramebuffers();
    if (backendsReady_) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        backendsReady_ = false;
    }
    if (descriptorPool_) vkDestroyDescriptorPool(context_.device, descriptorPool_, nullptr);
    descriptorPool_ = VK_NULL_HANDLE;
    if (renderPass_) vkDestroyRenderPass(context_.device, renderPass_, nullptr);
    renderPass_ = VK_NULL_HANDLE;
    if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
}

void ImGuiLayer::uploadFonts(VkCommandPool pool) {
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = pool;
    allocInfo.commandBufferCount = 1;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VIEWER_VK(vkAllocateCommandBuffers(context_.device, &allocInfo, &commands));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VIEWER_VK(vkBeginCommandBuffer(commands, &begin));
    ImGui_ImplVulkan_CreateFontsTexture(commands);
    VIEWER_VK(vkEndCommandBuffer(commands));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    VIEWER_VK(vkQueueSubmit(context_.queue, 1, &submit, VK_NULL_HANDLE));
    VIEWER_VK(vkQueueWaitIdle(context_.queue));
    vkFreeCommandBuffers(context_.device, pool, 1, &commands);
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ImGuiLayer::createFramebuffers(const Swapchain& swapchain) {
    for (VkImageView view : swapchain.views()) {
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = renderPass_;
        info.attachmentCount = 1;
        info.pAttachments = &view;
        info.width = swapchain.extent().width;
        info.height = swapchain.extent().height;
        info.layers = 1;
        VIEWER_VK(vkCreateFramebuffer(context_.device, &info, nullptr, &framebuffers_.emplace_back()));
    }
}

void ImGuiLayer::destroyFramebuffers() {
    for (VkFramebuffer framebuffer : framebuffers_) vkDestroyFramebuffer(context_.device, framebuffer, nullptr);
    framebuffers_.clear();
}

void ImGuiLayer::swapchainRecreated(const Swapchain& swapchain) {
    destroyFramebuffers();
    createFramebuffers(swapchain);
    ImGui_ImplVulkan_SetMinImageCount(2);
}

void ImGuiLayer::newFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::record(VkCommandBuffer commands, uint32_t image, VkExtent2D extent) {
    ImGui::Render();
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = renderPass_;
    begin.framebuffer = framebuffers_.at(image);
    begin.renderArea.extent = extent;
    vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), commands);
    vkCmdEndRenderPass(commands);
}

}  // namespace penumbra::viewer
