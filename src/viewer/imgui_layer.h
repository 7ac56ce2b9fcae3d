#pragma once
// Dear ImGui on the viewer's swapchain (Debian's imgui 1.86 GLFW and Vulkan backends): a render pass
// that loads the image Penumbra's frame was copied into and draws the panels over it.
#include <vector>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace penumbra::viewer {

class Swapchain;
class VulkanContext;

class ImGuiLayer {
public:
    // Install the window's own GLFW callbacks before: the backend chains to them.
    ImGuiLayer(VulkanContext& context, GLFWwindow* window, const Swapchain& swapchain, VkCommandPool pool);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void swapchainRecreated(const Swapchain& swapchain);
    void newFrame();
    // Draws the frame's ImGui data into swapchain image `image`, which is in TRANSFER_DST_OPTIMAL and
    // is left in TRANSFER_SRC_OPTIMAL.
    void record(VkCommandBuffer commands, uint32_t image, VkExtent2D extent);

private:
    void createFramebuffers(const Swapchain& swapchain);
    void destroyFramebuffers();
    void uploadFonts(VkCommandPool pool);
    void release();

    VulkanContext& context_;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
    std::vector<VkFramebuffer> framebuffers_;
    bool backendsReady_ = false;
};

}  // namespace penumbra::viewer
