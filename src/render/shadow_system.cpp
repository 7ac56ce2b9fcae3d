// ShadowSystem (penumbra/shadow_system.h): a Renderer whose frames are shadows alone, recorded into the
// caller's command buffer (Renderer::State::recordShadowFrame), and the hand-over of their descriptors as
// Vulkan handles.
#include "penumbra/shadow_system.h"

#include "core/error.h"
#include "gpu/device_access.h"
#include "render/caster_buffer_reads.h"
#include "render/renderer_state.h"

namespace penumbra {

namespace {

constexpr uint32_t kShaderReadOnlyOptimal = 5;  // VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
constexpr uint64_t kWholeSize = ~0ull;          // VK_WHOLE_SIZE

}  // namespace

struct ShadowSystem::Impl {
    Renderer renderer;
    ShadowFrameWrites writes;  // the latest frame's (kept: no allocation per frame)
    Impl(Device& device, Scene scene, const RendererOptions& options) : renderer(device, std::move(scene), options) {}
};

ShadowSystem::ShadowSystem(Device& device, Scene scene, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(device, std::move(scene), options)) {
    if (!impl_->renderer.state_->device.hasTimelineSemaphores())
        throw Error("ShadowSystem needs the timelineSemaphore feature (Vulkan 1.2) on " +
                    impl_->renderer.state_->device.info().name +
                    ": a caller's VkDevice must enable it and say so in ExternalVulkanDevice::timelineSemaphores");
}

ShadowSystem::ShadowSystem(Device& device, const CasterBuffers& casters, std::vector<Light> lights,
                           const RendererOptions& options)
    : ShadowSystem(device, readCasterBuffers(gpu::backend(device), casters, std::move(lights)), options) {}

ShadowSystem::~ShadowSystem() = default;

const Scene& ShadowSystem::scene() const { return impl_->renderer.scene(); }

void ShadowSystem::setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject) {
    impl_->renderer.setInstanceTransform(instance, worldFromObject);
}
void ShadowSystem::setInstanceCastShadows(uint32_t instance, bool castShadows) {
    impl_->renderer.setInstanceCastShadows(instance, castShadows);
}
void ShadowSystem::setLight(uint32_t light, const Light& value) { impl_->renderer.setLight(light, value); }
void ShadowSystem::setMaterial(uint32_t material, const Material& value) { impl_->renderer.setMaterial(material, value); }

ShadowFrameBindings ShadowSystem::recordFrame(uint64_t vkCommandBuffer, const Settings& settings, const CameraView& view,
                                              const ShadowViewDepth* depth) {
    Renderer::State& state = *impl_->renderer.state_;
    const gpu::Device::ExternalFrameEnd end =
        state.recordShadowFrame(vkCommandBuffer, settings, view, depth, impl_->writes);
    ShadowFrameBindings bindings;
    bindings.frameIndex = end.frameIndex;
    bindings.vkCompletionSemaphore = end.vkTimelineSemaphore;
    bindings.completionValue = end.signalValue;
    for (const gpu::SpecConstant& constant : state.litPassScratch.specialization)
        if (constant.id >= 2 && constant.id < 2 + bindings.specialization.size())
            bindings.specialization[constant.id - 2] = constant.value;
    for (uint32_t i = 0; i < kShadowBindingCount; ++i) {
        const gpu::DescriptorWrite& write = impl_->writes[i];
        ShadowDescriptorResource& out = bindings.descriptors[i];
        out.binding = kShadowDescriptors[i].binding;
        out.type = kShadowDescriptors[i].type;
        if (out.type == ShadowDescriptorType::CombinedImageSampler) {
            out.vkImageView = state.device.nativeImageView(write.texture);
            out.vkSampler = state.device.nativeSampler(write.sampler);
            out.vkImageLayout = kShaderReadOnlyOptimal;
        } else {
            out.vkBuffer = state.device.nativeBuffer(write.buffer);
            out.offset = write.offset;
            out.range = write.size ? write.size : kWholeSize;
        }
    }
    return bindings;
}

std::vector<FrameStats> ShadowSystem::takeCompletedFrames() { return impl_->renderer.takeCompletedFrames(); }

void ShadowSystem::waitIdle() { impl_->renderer.waitIdle(); }

}  // namespace penumbra
