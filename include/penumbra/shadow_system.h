#pragma once
// Penumbra as the shadow system of an engine that keeps its own renderer: it plans the shadows of a
// scene's lights for the engine's camera, records the shadow passes (atlases or virtual pages, with the
// view's depth they need) into the engine's command buffer, and hands over the descriptors that the
// engine's shaders read through <penumbra/shadows.glsl>. No Vulkan header is needed here;
// <penumbra/vulkan.h> adds the Vulkan-typed helpers (the descriptor set layout, the descriptor writes,
// the completion signal). docs/engine-integration.md walks through it.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include <penumbra/camera.h>
#include <penumbra/caster_buffers.h>
#include <penumbra/device.h>
#include <penumbra/renderer.h>
#include <penumbra/scene.h>
#include <penumbra/settings.h>
#include <penumbra/shadows/bindings.h>

namespace penumbra {

// What one descriptor of <penumbra/shadows.glsl> binds this frame (Vulkan handles as integers).
struct ShadowDescriptorResource {
    uint32_t binding = 0;  // kShadowBinding* (plus the shader's PENUMBRA_SHADOW_BINDING_BASE)
    ShadowDescriptorType type = ShadowDescriptorType::UniformBuffer;
    uint64_t vkBuffer = 0, offset = 0, range = 0;  // uniform and storage buffers (VkBuffer)
    uint64_t vkImageView = 0, vkSampler = 0;       // combined image samplers (VkImageView, VkSampler)
    uint32_t vkImageLayout = 0;                    // VkImageLayout the image is in: SHADER_READ_ONLY_OPTIMAL
};

// The engine's depth buffer of the frame's view (optional): the virtual pages are marked from it and the
// tight cascade fit reduces it, in place of the depth prepass Penumbra otherwise draws of its scene.
struct ShadowViewDepth {
    // VkImage of VK_FORMAT_D32_SFLOAT, one level and layer, the view's width x height, made with SAMPLED
    // and DEPTH_STENCIL_ATTACHMENT usage, holding the view's depth as CameraView's projection (reversed
    // Z: 1 near, 0 far or empty). When recordFrame's commands start it is in DEPTH_ATTACHMENT_OPTIMAL
    // with the engine's writes made by earlier commands (its depth prepass); they leave it there again.
    uint64_t vkImage = 0;
    // A VkImageView of it: 2D, VK_IMAGE_ASPECT_DEPTH_BIT, the one level and layer (its attachment view
    // does). Penumbra samples through it and never destroys either.
    uint64_t vkImageView = 0;
};

// A recorded shadow frame: what to bind, and the signal its submission must carry.
struct ShadowFrameBindings {
    uint64_t frameIndex = 0;
    // The submission of the command buffer must signal this timeline VkSemaphore to completionValue
    // (e.g. a VkSemaphoreSubmitInfo in vkQueueSubmit2): Penumbra reuses the frame's memory, and reads
    // its timings and statistics, once it is reached.
    uint64_t vkCompletionSemaphore = 0;
    uint64_t completionValue = 0;
    // The frame's values of the specialization constants PENUMBRA_SHADOW_CONSTANT_ID + 0 .. + 3 of
    // <penumbra/shadows.glsl> (spot/point kinds, spot filter, directional kinds, directional filter): a
    // shader that defines it and is specialized with them compiles only the sampling this frame's lights
    // need; one that does not define it compiles every kind and needs none.
    std::array<uint32_t, 4> specialization{};
    // In binding order (kShadowDescriptors). Buffers and views stay valid until the next frame call
    // that reuses the frame's ring slot (DeviceOptions::framesInFlight calls later).
    std::array<ShadowDescriptorResource, kShadowBindingCount> descriptors;
};

class ShadowSystem {
public:
    // The casters and lights of `scene` (a loaded glTF or a SceneBuilder scene) on `device`, which may be
    // the caller's own VkDevice (<penumbra/vulkan.h>; it must enable the timelineSemaphore feature and
    // say so in ExternalVulkanDevice). Throws penumbra::Error naming what is wrong.
    ShadowSystem(Device& device, Scene scene, const RendererOptions& options = {});
    // The engine's own caster geometry in its GPU buffers (penumbra/caster_buffers.h) and its lights:
    // the constructor reads the buffers and textures once on the device's queue (after the writes of
    // everything submitted to it before, waiting for the copies) into Penumbra's own meshlet-ordered copy;
    // the engine keeps and may change or free its objects afterwards. Instance i of `casters` is instance
    // i of setInstanceTransform / setInstanceCastShadows, light i of `lights` light i of setLight and of
    // the shadow light table. Throws penumbra::Error (one line) for a description that cannot be read.
    ShadowSystem(Device& device, const CasterBuffers& casters, std::vector<Light> lights,
                 const RendererOptions& options = {});
    ~ShadowSystem();
    ShadowSystem(const ShadowSystem&) = delete;
    ShadowSystem& operator=(const ShadowSystem&) = delete;

    const Scene& scene() const;

    // ---- changes between frames, as Renderer's: only what changed is uploaded and redrawn.
    void setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject);
    void setInstanceCastShadows(uint32_t instance, bool castShadows);
    void setLight(uint32_t light, const Light& value);  // the light table follows Scene::lights
    void setMaterial(uint32_t material, const Material& value);  // scene().materials (from CasterBuffers: one per
                                                                   // distinct shadow mode, alpha and texture)

    // Records this frame's shadow passes into `vkCommandBuffer` (a primary VkCommandBuffer of the
    // device's queue family, in the recording state, outside a render pass), for the camera `view`
    // (its width and height are the caller's viewport: the virtual pages' resolution follows them).
    // Synchronisation (docs/engine-integration.md): the commands wait for nothing of the caller's and
    // touch none of its resources; when they end, every image of the returned descriptors is in
    // SHADER_READ_ONLY_OPTIMAL and every write is visible to fragment and compute shader reads that
    // follow in the command buffer. Submit the command buffer, signalling the returned completion
    // value, before the next call. On a throw (one line, penumbra::Error) the command buffer may hold
    // part of the frame: reset it. With `depth`, the engine's depth buffer of this view (above) serves
    // the virtual pages and the tight fit: the commands then wait for the engine's depth writes.
    ShadowFrameBindings recordFrame(uint64_t vkCommandBuffer, const Settings& settings, const CameraView& view,
                                    const ShadowViewDepth* depth = nullptr);

    // Statistics of the frames the GPU has finished since the last call, oldest first (as Renderer's;
    // the main-view fields are empty: mainView is "none").
    std::vector<FrameStats> takeCompletedFrames();
    // Waits until every recorded frame's completion value is reached (they must all be submitted).
    void waitIdle();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra
