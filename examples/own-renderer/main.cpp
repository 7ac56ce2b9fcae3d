// penumbra_own_renderer SCENE OUT.png WIDTH HEIGHT [--depth-prepass] [--set key=value ...]
// An engine's own Vulkan renderer (its device, mesh upload, materials and forward pass: vulkan_context.h,
// forward_pass.h) with Penumbra as its shadow system: ShadowSystem records the shadow passes into the
// engine's command buffer, and the engine's fragment shader calls penumbraShadow
// (<penumbra/shadows.glsl>). Writes the colour image to OUT.png and light 0's shadow term, as the
// engine's pass computed it, to OUT.shadow.png (8-bit grayscale, the convention of `penumbra render
// --aov shadow`). --depth-prepass: the engine draws its depth first and hands it to ShadowSystem (the
// virtual pages and the tight cascade fit read it), then shades against it. --set: Penumbra's settings
// (docs/settings.md), as `penumbra render --set`. PENUMBRA_DEVICE=cpu picks lavapipe (else a GPU);
// PENUMBRA_VALIDATION=1 turns on the validation layer, whose first message fails the run.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <penumbra/penumbra.h>
#include <penumbra/vulkan.h>

#include "forward_pass.h"
#include "vulkan_context.h"

namespace {

uint32_t parseSize(const char* text, const char* what) {
    char* end = nullptr;
    const unsigned long value = std::strtoul(text, &end, 10);
    if (*text == '\0' || *end != '\0' || value == 0 || value > 16384)
        throw std::runtime_error(std::string(what) + " must be 1..16384, got '" + text + "'");
    return uint32_t(value);
}

// Light 0 for the engine's own lighting: toward a sun (w = 0) or a spot or point light's position (w = 1).
glm::vec4 lightZero(const penumbra::Scene& scene) {
    if (scene.lights.empty()) return {0.0f, 1.0f, 0.0f, 0.0f};
    const penumbra::Light& light = scene.lights[0];
    if (light.type == penumbra::LightType::Directional) return glm::vec4(-light.wsDirection, 0.0f);
    return glm::vec4(light.wsPosition, 1.0f);
}

std::string shadowPath(const std::string& out) {
    const std::string suffix = ".png";
    const bool png = out.size() > suffix.size() && out.compare(out.size() - suffix.size(), suffix.size(), suffix) == 0;
    return (png ? out.substr(0, out.size() - suffix.size()) : out) + ".shadow.png";
}

// One frame: Penumbra's shadow passes, then the engine's forward pass, in one command buffer whose
// submission signals the shadow frame's completion value.
void renderFrame(own::VulkanContext& vulkan, penumbra::ShadowSystem& shadows, own::ForwardPass& forward,
                 const penumbra::Settings& settings, const penumbra::CameraView& view, bool depthPrepass) {
    VkCommandBuffer cb = VK_NULL_HANDLE;
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = vulkan.commandPool;
    alloc.commandBufferCount = 1;
    OWN_VK(vkAllocateCommandBuffers(vulkan.device, &alloc, &cb));
    struct FreeOnExit {  // also when recording fails
        own::VulkanContext& vulkan;
        VkCommandBuffer cb;
        ~FreeOnExit() { vkFreeCommandBuffers(vulkan.device, vulkan.commandPool, 1, &cb); }
    } freeOnExit{vulkan, cb};
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    OWN_VK(vkBeginCommandBuffer(cb, &begin));
    const glm::vec4 light = lightZero(shadows.scene());
    if (depthPrepass) forward.recordDepthPrepass(cb, view.clipFromWorld, light);
    const penumbra::ShadowFrameBindings frame =
        penumbra::recordShadowFrame(shadows, cb, settings, view, depthPrepass ? forward.depthImage() : VK_NULL_HANDLE,
                                    depthPrepass ? forward.depthView() : VK_NULL_HANDLE);
    penumbra::writeShadowDescriptors(vulkan.device, forward.shadowSet(), frame);
    forward.record(cb, view.clipFromWorld, light);
    OWN_VK(vkEndCommandBuffer(cb));
    VkCommandBufferSubmitInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    commandInfo.commandBuffer = cb;
    const VkSemaphoreSubmitInfo done = penumbra::shadowFrameSignal(frame);
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &commandInfo;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &done;
    OWN_VK(vkQueueSubmit2(vulkan.queue, 1, &submit, VK_NULL_HANDLE));
    OWN_VK(vkQueueWaitIdle(vulkan.queue));
}

int run(int argc, char** argv) {
    const char* usage = "usage: penumbra_own_renderer SCENE OUT.png WIDTH HEIGHT [--depth-prepass] [--set key=value ...]";
    if (argc < 5) throw std::runtime_error(usage);
    const std::string out = argv[2];
    const uint32_t width = parseSize(argv[3], "WIDTH"), height = parseSize(argv[4], "HEIGHT");
    bool depthPrepass = false;
    penumbra::Settings settings;  // the defaults, with --set, then the CLI's scene defaults (shadows.maxDistance)
    for (int i = 5; i < argc; ++i) {
        const std::string option = argv[i];
        if (option == "--depth-prepass") depthPrepass = true;
        else if (option == "--set" && i + 1 < argc) penumbra::applySettingOverride(settings, argv[++i]);
        else throw std::runtime_error(usage);
    }
    penumbra::validateSettings(settings);
    const char* deviceChoice = std::getenv("PENUMBRA_DEVICE");
    const char* validation = std::getenv("PENUMBRA_VALIDATION");
    own::VulkanContext vulkan(deviceChoice ? deviceChoice : "gpu", validation && std::string(validation) == "1");
    int messages = 0;
    {
        const penumbra::Scene scene = penumbra::loadScene(argv[1]);
        const penumbra::CameraView view = penumbra::resolveCameraView(scene, width, height);
        for (const std::string& warning : penumbra::applySceneDefaults(settings, scene, view))
            std::fprintf(stderr, "penumbra_own_renderer: warning: %s\n", warning.c_str());
        penumbra::Device device(penumbra::externalVulkanDevice(vulkan.instance, vulkan.physicalDevice, vulkan.device,
                                                               vulkan.queue, vulkan.queueFamily, false, true));
        own::ForwardPass forward(vulkan, scene, width, height, OWN_RENDERER_SPIRV_DIR, depthPrepass);
        // The engine's casters are its own buffers; ShadowSystem reads them once, here.
        penumbra::ShadowSystem shadows(device, forward.casterBuffers(scene), scene.lights);
        renderFrame(vulkan, shadows, forward, settings, view, depthPrepass);
        shadows.waitIdle();
        penumbra::Image color(width, height, 3), shadow(width, height, 1);
        color.pixels = forward.colorPixels();
        shadow.pixels = forward.shadowPixels();
        penumbra::writePng(color, out);
        penumbra::writePng(shadow, shadowPath(out));
    }
    messages = vulkan.validationMessages;
    if (messages > 0) throw std::runtime_error(std::to_string(messages) + " Vulkan validation message(s)");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "penumbra_own_renderer: %s\n", error.what());
        return 1;
    }
}
