#pragma once
// The GPU device: instance and physical-device selection (or a caller's VkDevice), memory blocks,
// object pools with reused slots, the ring of frames in flight with deferred destruction, the
// pipeline cache and asynchronous pipeline builds, timestamps and validation. The only entry point
// render/ has to the GPU. Vulkan stays inside src/gpu/*.cpp.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/command_list.h"
#include "gpu/device_faults.h"
#include "gpu/types.h"
#include "penumbra/device.h"
#include "penumbra/image.h"

namespace penumbra::gpu {

class FrameGraph;
// The public options and, for tests, the faults to inject.
struct DeviceOptions : penumbra::DeviceOptions {
    DeviceOptions() = default;
    DeviceOptions(const penumbra::DeviceOptions& options, const DeviceFaultInjection& faults = {})
        : penumbra::DeviceOptions(options), faults(faults) {}
    DeviceFaultInjection faults;
};
using DeviceInfo = penumbra::DeviceInfo;

class Device {
public:
    // Throws penumbra::Error("no Vulkan device ...") with one line when none fits the choice.
    explicit Device(const DeviceOptions& options);
    // On a VkDevice the caller made and keeps (penumbra/vulkan.h lists what it must enable).
    Device(const ExternalVulkanDevice& external, const DeviceOptions& options);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    const DeviceInfo& info() const;
    static std::vector<DeviceInfo> listDevices();
    uint32_t maxImageSize() const;            // maxImageDimension2D (or the fault injection's smaller one)
    uint64_t maxStorageBufferRange() const;   // the largest storage buffer a shader may bind (or the fault injection's)
    uint32_t maxDrawIndirectCount() const;    // draws one indirect multi-draw may issue (1 without multiDrawIndirect)
    bool lost() const;                        // a submission or wait returned VK_ERROR_DEVICE_LOST
    bool hasTimestamps() const;
    // shaderInt64 + shaderBufferInt64Atomics enabled (the visibility-buffer main view needs them).
    bool hasBufferInt64Atomics() const;
    // shaderStorageBufferArrayDynamicIndexing enabled: a binding may be an array of storage buffers that
    // a shader indexes with a dynamically uniform index (the culling lists split over buffers need it).
    bool hasStorageBufferArrayIndexing() const;
    bool hasTimelineSemaphores() const;  // the timelineSemaphore feature is enabled (external frames)
    // shaderStorageImageExtendedFormats enabled: storage images of Format::R16Unorm (Vulkan then requires
    // their support), what halves the virtual shadow maps' pools.
    bool hasStorageImageExtendedFormats() const;
    const DeviceFaultInjection& faults() const;  // what the device's options inject (tests)

    // ---- objects. destroy() is deferred: the Vulkan objects go when no frame in flight can use them.
    BufferHandle createBuffer(size_t size, uint32_t usage, MemoryKind memory, const void* initialData = nullptr,
                              const std::string& debugName = "");
    void writeBuffer(BufferHandle buffer, const void* data, size_t size, size_t offset = 0);  // HostVisible only
    void* mappedPointer(BufferHandle buffer);
    // The Vulkan objects behind handles, as integers (VkBuffer, VkImageView, VkSampler): what an
    // embedder's own descriptors bind (ShadowSystem). Valid while the handle lives.
    uint64_t nativeBuffer(BufferHandle buffer) const;
    uint64_t nativeImageView(TextureHandle texture) const;
    uint64_t nativeSampler(SamplerHandle sampler) const;
    uint64_t bufferSize(BufferHandle buffer) const;
    TextureHandle createTexture(const TextureDesc& desc);
    const TextureDesc& textureDesc(TextureHandle texture) const;
    // A caller's depth image (VK_FORMAT_D32_SFLOAT, one level and layer, SAMPLED and DEPTH_STENCIL_ATTACHMENT
    // usage) and its depth-aspect view, which passes sample; neither is ever destroyed here.
    TextureHandle importDepthTexture(uint64_t vkImage, uint64_t vkImageView, uint32_t width, uint32_t height,
                                     const std::string& debugName);
    // The caller's own commands, recorded before the next pass, last wrote `texture` as `usage` (and left
    // it in that usage's layout): the next pass that uses it waits for them.
    void assumeWritten(TextureHandle texture, Usage usage);
    // Uploads level 0 (tightly packed RGBA8 / R8 ...) and builds the mip chain; leaves it ShaderRead.
    void uploadTexture(TextureHandle texture, std::span<const uint8_t> pixels);
    // Wraps a caller's VkImage (ExternalTarget::image) as a transfer destination; owns nothing.
    TextureHandle importTexture(const ExternalTarget& target, const std::string& debugName);
    SamplerHandle createSampler(const SamplerDesc& desc);
    TextureTableHandle createTextureTable(std::span<const TextureHandle> textures, SamplerHandle sampler);
    // One sampler per texture (samplers.size() == textures.size()).
    TextureTableHandle createTextureTable(std::span<const TextureHandle> textures, std::span<const SamplerHandle> samplers);
    PipelineHandle createGraphicsPipeline(const GraphicsPipelineDesc& desc);
    // The same, built on the device's worker thread; bind it only once pipelineReady() says so.
    PipelineHandle createGraphicsPipelineAsync(const GraphicsPipelineDesc& desc);
    bool pipelineReady(PipelineHandle pipeline);
    void waitForPipeline(PipelineHandle pipeline);
    uint32_t pipelineBuildsPending();
    void waitForPipelineBuilds();  // every asynchronous build requested so far
    PipelineHandle createComputePipeline(const ComputePipelineDesc& desc);
    void destroy(BufferHandle handle);
    void destroy(TextureHandle handle);
    void destroy(SamplerHandle handle);
    void destroy(PipelineHandle handle);
    void destroy(TextureTableHandle handle);

    // ---- frames in flight (DeviceOptions::framesInFlight slots, each with its fence, command pool,
    // timestamp range and upload ring). beginFrame waits only for the frame that last used the slot.
    uint32_t framesInFlight() const;
    uint64_t nextFrameIndex() const;  // the index the next beginFrame gives its frame
    CommandList beginFrame();
    // Host-visible memory for this frame's data (uniforms, lights, staging), valid while it is in
    // flight; only between beginFrame and submitFrame. An allocation that grows the ring leaves the
    // earlier slices' buffer valid until the frame is submitted (its memory until the frame is done).
    FrameAllocation allocateFrameData(uint64_t size, uint64_t alignment = 256);
    // Ends and submits the frame with its fence (one vkQueueSubmit); `sync` adds the caller's
    // semaphores. Returns the frame's index.
    uint64_t submitFrame(CommandList& commands, const ExternalTarget* sync = nullptr);
    // A frame recorded into a caller's primary command buffer (in the recording state, of this device's
    // queue family) instead of the slot's own: the ring, timers and readbacks work as for beginFrame.
    // endExternalFrame submits nothing: the caller submits the command buffer and signals the returned
    // timeline value, which the slot waits for before it is used again (and readbacks and timers are
    // read). Needs hasTimelineSemaphores().
    CommandList beginExternalFrame(uint64_t vkCommandBuffer);
    struct ExternalFrameEnd {
        uint64_t frameIndex = 0;
        uint64_t vkTimelineSemaphore = 0;  // VkSemaphore (VK_SEMAPHORE_TYPE_TIMELINE)
        uint64_t signalValue = 0;          // what the caller's submission signals it to
    };
    ExternalFrameEnd endExternalFrame(CommandList& commands);
    // Drops the frame being recorded (after an error while recording it): nothing is submitted, the
    // slot is free for the next beginFrame, objects destroyed meanwhile go with the next submission.
    void abandonFrame(CommandList& commands);
    // Copies `source` (GPU-written, e.g. counters) at the end of this frame's work into memory the host
    // reads once the frame is done: the bytes arrive in CompletedFrame::readback, in call order, and
    // the result is where these ones start there.
    uint64_t readBackAtFrameEnd(CommandList& commands, const BufferSlice& source);
    void waitFrame(uint64_t frameIndex);  // returns once that frame has finished on the GPU
    void waitIdle();                      // every submitted frame (fence waits, no vkDeviceWaitIdle)
    // After waitIdle: frees memory blocks that hold nothing (a renderer's end, say).
    void trimMemory();
    // Frames finished since the last call, oldest first (timestamps per pass, submit-to-fence time).
    std::vector<CompletedFrame> takeCompletedFrames();
    // The same without a heap allocation once warm: the frames finished since the last
    // releaseCompletedFrames(), read in place (valid until the next call of beginFrame, waitFrame,
    // waitIdle or releaseCompletedFrames), then released; their storage serves the next frames.
    std::span<CompletedFrame> completedFrames();
    void releaseCompletedFrames();
    // The synchronisation state of every buffer and texture, and the passes of the frame being
    // recorded when FrameGraph::recordPasses is on (penumbra graph).
    FrameGraph& frameGraph();

    // ---- one-off work outside the frame ring (load time, debugging): waits for completion.
    // Recorded and submitted outside any frame's recording: its passes join the frame graph's states
    // in submission order.
    CommandList beginCommands();
    void submitAndWait(CommandList& commands);
    // Copies a whole buffer to host memory (waits for the GPU; tests and debugging).
    std::vector<uint8_t> readBuffer(BufferHandle buffer);
    // Reads of a caller's own objects (ShadowSystem's caster buffers), after the writes of everything
    // submitted to the queue before; they wait for the GPU. `size` bytes of a VkBuffer made with
    // TRANSFER_SRC usage, from `offset`:
    std::vector<uint8_t> readExternalBuffer(uint64_t vkBuffer, uint64_t offset, uint64_t size);
    // Level 0, layer 0 of a 2D VkImage made with TRANSFER_SRC usage, in `vkImageLayout` (left so), as
    // tightly packed RGBA8 (R8's value becomes the alpha of white; BGRA is swizzled). Formats: R8_UNORM,
    // R8G8B8A8_UNORM / _SRGB, B8G8R8A8_UNORM / _SRGB.
    std::vector<uint8_t> readExternalImageRgba8(uint64_t vkImage, uint32_t vkFormat, uint32_t width, uint32_t height,
                                                uint32_t vkImageLayout);

    ObjectCounts objectCounts() const;
    // Device memory this process uses: VK_EXT_memory_budget's heap usage where the driver has it,
    // else the bytes held in the allocator's blocks.
    uint64_t deviceMemoryBytes() const;

    // Fence and semaphore status polls made by waits so far (DeviceOptions::spinWait; 0 without it).
    uint64_t spinWaitPolls() const;

    // Validation messages (warnings and errors) seen so far; tests fail on any.
    uint32_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;

    struct Impl;
    Impl& impl() { return *impl_; }

private:
    void createOwnDevice(const DeviceOptions& options);
    void initialize();
    void release();  // the destructor's work; also undoes a constructor that failed half-way
    std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra::gpu
