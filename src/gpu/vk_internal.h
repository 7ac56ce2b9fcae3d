#pragma once
// Internal to src/gpu/: the Vulkan side of the Device. Nothing outside src/gpu/ includes this.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/error.h"
#include "gpu/device.h"
#include "gpu/frame_graph.h"
#include "gpu/handle_pool.h"
#include "gpu/memory_allocator.h"

namespace penumbra::gpu {

const char* vkResultName(VkResult result);

// Always-on check: names the call and the VkResult in a one-line error.
#define VK_CHECK(call)                                                                                 \
    do {                                                                                               \
        const VkResult vkCheckResult_ = (call);                                                        \
        if (vkCheckResult_ != VK_SUCCESS)                                                              \
            throw ::penumbra::Error(std::string("Vulkan call failed: ") + #call + " returned " +      \
                                    ::penumbra::gpu::vkResultName(vkCheckResult_));                   \
    } while (0)

struct BufferResource {
    VkBuffer buffer = VK_NULL_HANDLE;
    MemoryAllocation memory;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
};

struct TextureResource {
    VkImage image = VK_NULL_HANDLE;
    bool imported = false;  // a caller's VkImage (importTexture): never destroyed here
    bool importedView = false;  // and its view too (importDepthTexture)
    MemoryAllocation memory;
    VkImageView view = VK_NULL_HANDLE;
    TextureDesc desc;
    VkFormat format = VK_FORMAT_UNDEFINED;
};

struct PipelineResource {
    VkPipeline pipeline = VK_NULL_HANDLE;  // VK_NULL_HANDLE while an asynchronous build runs
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout pushSetLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    VkShaderStageFlags pushStages = 0;  // of the push-constant range: the stages whose shaders use it
    std::vector<BindingDesc> bindings;
    std::string reuseKey;  // everything the compiled pipeline depends on (pipeline_reuse.cpp)
};

// A compiled pipeline whose handle was destroyed, kept with its layouts for the next pipeline created
// from the same description (pipeline_reuse.cpp).
struct ParkedPipeline {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout pushSetLayout = VK_NULL_HANDLE;
};

struct TextureTableResource {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    uint32_t count = 0;
};

// Vulkan objects whose handle was destroyed but which a frame in flight may still use: destroyed
// when the frame they are attached to has finished on the GPU (Granite / Filament style).
struct Garbage {
    std::vector<BufferResource> buffers;
    std::vector<TextureResource> textures;
    std::vector<PipelineResource> pipelines;
    std::vector<VkSampler> samplers;
    std::vector<TextureTableResource> tables;
    uint32_t count() const {
        return uint32_t(buffers.size() + textures.size() + pipelines.size() + samplers.size() + tables.size());
    }
};

// One slot of the ring of frames in flight.
struct FrameContext {
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    bool inFlight = false;
    uint64_t frameIndex = 0;
    std::chrono::steady_clock::time_point submitTime;
    // The timers of the frame it holds (the first timerCount names), lent to the frame's CommandList
    // while it records and kept with their strings' storage from frame to frame (no allocation once
    // warm).
    std::vector<std::string> timerNames;
    uint32_t timerCount = 0;
    std::vector<uint32_t> openTimers;
    Garbage garbage;
    // Upload ring: one host-visible buffer per slot, bump-allocated, reset when the slot is reused.
    BufferHandle uploadBuffer;
    uint64_t uploadCapacity = 0;
    uint64_t uploadUsed = 0;
    std::vector<std::pair<uint64_t, uint64_t>> readbackRanges;  // (offset, size) in the upload ring
    // Ring buffers this frame outgrew: their handles stay valid (earlier allocations' slices name them)
    // until the frame is submitted or abandoned, then they go with the frame's garbage.
    std::vector<BufferHandle> outgrownUploads;
    // Recorded into a caller's command buffer (beginExternalFrame): done once the Device's timeline
    // semaphore reaches timelineValue (the caller's submission signals it), not when the fence signals.
    bool external = false;
    uint64_t timelineValue = 0;
};

// A graphics pipeline built on the Device's worker thread.
struct PipelineJob {
    uint32_t id = 0;
    GraphicsPipelineDesc desc;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    uint32_t textureCount = 0;
};

struct Device::Impl {
    DeviceOptions options;
    DeviceInfo info;
    bool ownsDevice = true;  // false when built on a caller's VkDevice (penumbra/vulkan.h)
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    bool memoryBudget = false;  // VK_EXT_memory_budget enabled
    VkQueryPool timestampPool = VK_NULL_HANDLE;
    uint32_t timestampsPerFrame = 128;
    bool timestampsSupported = false;
    bool bufferInt64Atomics = false;  // enabled on devices it creates; external devices: not known, off
    bool storageBufferArrayIndexing = false;  // shaderStorageBufferArrayDynamicIndexing, as bufferInt64Atomics
    bool timelineSemaphores = false;  // the timelineSemaphore feature (external frames need it)
    bool storageImageExtendedFormats = false;  // shaderStorageImageExtendedFormats enabled (R16Unorm storage)
    // The timeline semaphore a caller's submission of an external frame signals (made by the first one).
    VkSemaphore externalTimeline = VK_NULL_HANDLE;
    uint64_t externalTimelineValue = 0;
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;
    VkPipelineCache pipelineCache = VK_NULL_HANDLE;
    std::string pipelineCacheFile;  // "" = not persisted

    std::unique_ptr<MemoryAllocator> memory;
    HandlePool<BufferResource> buffers;
    HandlePool<TextureResource> textures;
    HandlePool<VkSampler> samplers;
    HandlePool<PipelineResource> pipelines;
    HandlePool<TextureTableResource> tables;
    uint64_t objectsCreated = 0;
    std::array<char, 48> lastObjectName{};  // noteCreated's last
    uint64_t submits = 0;
    uint64_t deviceWaits = 0;
    uint64_t debugNamesSet = 0;

    // Frames in flight.
    std::vector<FrameContext> frames;
    uint64_t nextFrameIndex = 0;  // index of the next frame beginFrame() starts
    int32_t recordingSlot = -1;   // slot between beginFrame and submitFrame, else -1
    Garbage pendingGarbage;       // destroyed since the last submit: attached to the next one
    // Finished frames: the first completedCount are this time's; the elements after them keep their
    // storage for the next frames (no allocation once warm).
    std::vector<CompletedFrame> completed;
    size_t completedCount = 0;
    // Scratch of CommandList's copy, clear and rendering commands (kept to reuse their memory).
    std::vector<VkClearRect> scratchClears;
    std::vector<VkRenderingAttachmentInfo> scratchAttachments;
    std::vector<FrameContext*> scratchInFlight;

    // The frame graph's resource states (frame_graph.h), shared by frames and one-off lists, and the
    // barrier structures CommandList::pass fills (kept to reuse their memory).
    FrameGraph frameGraph;
    std::vector<VkBufferMemoryBarrier2> bufferBarriers;
    std::vector<VkImageMemoryBarrier2> imageBarriers;

    // One-off submissions (uploads at load time, readbacks outside a frame).
    VkCommandPool immediatePool = VK_NULL_HANDLE;
    VkFence immediateFence = VK_NULL_HANDLE;

    // Asynchronous pipeline builds: the worker only calls vkCreateGraphicsPipelines; finished
    // pipelines are moved into the pool on the calling thread (collectPipelineBuilds).
    std::thread worker;
    std::mutex jobsMutex;
    std::condition_variable jobsChanged;
    std::deque<PipelineJob> jobs;
    std::vector<std::pair<uint32_t, VkPipeline>> finishedBuilds;
    std::vector<std::string> buildErrors;
    uint32_t buildsRunning = 0;
    bool stopWorker = false;

    // Compiled pipelines kept after their handles died (oldest first out past kMaxParkedPipelines):
    // drivers compile at creation (lavapipe spends most of a small frame's time there), and a second
    // Renderer on this device, a reloaded scene or a settings round trip asks for the same pipelines.
    static constexpr size_t kMaxParkedPipelines = 256;
    std::unordered_map<std::string, ParkedPipeline> parkedPipelines;
    std::deque<std::string> parkedOrder;
    std::atomic<uint64_t> pipelinesCompiled = 0;  // vkCreate*Pipelines calls (the worker's too)
    uint64_t pipelinesReused = 0;
    // Moves a parked pipeline of `key` into `p` (true), or leaves `p` alone (false).
    bool takeParkedPipeline(const std::string& key, PipelineResource& p);
    // Parks a compiled pipeline no frame uses any more, or destroys it when one of its key is parked.
    void parkOrDestroy(PipelineResource& p);
    void destroyParkedPipelines();

    // Device loss (real, or injected by options.faults): once lost, no wait is made again and every
    // frame or one-off submission throws at once.
    bool lost = false;
    std::string lostAt;           // "submitting frame 3 (passes a, b)"
    uint64_t submissionCalls = 0;  // queue submissions attempted (fault injection counts these)
    uint64_t fenceWaits = 0;       // waits for a submission (fault injection counts these)
    uint64_t spinWaitPolls = 0;    // status polls of spinning waits (options.spinWait)
    [[noreturn]] void throwLost(const std::string& where, VkResult result);
    void throwIfLost() const;
    // What a submission holds, spelled out only for an error message ("frame 3 (passes
    // shadows.directional, main)" or a fixed text): a frame's submission allocates nothing.
    struct SubmissionName {
        std::string_view text;  // a fixed description; empty for a frame
        uint64_t frameIndex = 0;
        std::span<const std::string> passes;
        std::string describe() const;
    };
    // vkQueueSubmit2 / vkWaitForFences through the loss checks and the fault injection; `what`
    // names the work in the error.
    void queueSubmit(const VkSubmitInfo2& submit, VkFence fence, const SubmissionName& what);
    void waitForFence(VkFence fence, const SubmissionName& what);
    // The frame ring's steps (frames.cpp): a slot begun into its own or a caller's command buffer, its
    // closing commands, and its hand-over to the GPU.
    CommandList beginSlot(Device& owner, VkCommandBuffer external);
    void endSlotCommands(FrameContext& frame, CommandList& commands);
    void closeSlot(FrameContext& frame, CommandList& commands);
    void retireOutgrownUploads(FrameContext& frame);  // into frame.garbage
    // Waits for an external frame's timeline value: an error names a command buffer never submitted.
    void waitForTimeline(uint64_t value, const SubmissionName& what);
    // Scratch of CommandList::pushDescriptors (capacity kept: no allocation per pass once warm).
    std::vector<VkWriteDescriptorSet> scratchWrites;
    std::vector<VkDescriptorBufferInfo> scratchBufferInfos;
    std::vector<VkDescriptorImageInfo> scratchImageInfos;
    std::vector<uint64_t> scratchTicks;
    std::string scratchName;               // CommandList::joinName
    std::vector<ResourceUse> scratchUses;  // CommandList::joinUses

    mutable std::mutex messagesMutex;
    std::vector<std::string> validationMessages;

    // Records and runs a one-off command buffer and waits for it (load-time work).
    template <typename Record>
    void immediate(Record&& record);
    VkCommandBuffer beginImmediate();
    void endImmediate(VkCommandBuffer commandBuffer);
    VkShaderModule loadShader(const std::string& name);
    void setDebugName(VkObjectType type, uint64_t handle, const std::string& name);
    // Counts an object made (DeviceObjectCounts::objectsCreated) and keeps its name as the last one's.
    void noteCreated(std::string_view name) {
        ++objectsCreated;
        const size_t length = std::min(name.size(), lastObjectName.size() - 1);
        std::copy_n(name.data(), length, lastObjectName.data());
        lastObjectName[length] = '\0';
    }
    Garbage& garbageList() { return recordingSlot >= 0 ? frames[recordingSlot].garbage : pendingGarbage; }
    void destroyGarbage(Garbage& garbage);
    void destroyNow(BufferResource& resource);
    void destroyNow(TextureResource& resource);
    void destroyNow(PipelineResource& resource);
    void destroyNow(TextureTableResource& resource);
    // Waits for the slot's frame (if in flight), reads its timestamps, frees its garbage.
    void retireFrame(FrameContext& frame);
    void createFrames(uint32_t count);
    void createUploadRings(Device& owner);  // each slot's upload ring, made up front
    void destroyFrames();
    void startWorker();
    void stopWorkerThread();
    VkPipeline buildGraphicsPipeline(const GraphicsPipelineDesc& desc, VkPipelineLayout layout, uint32_t textureCount);
    // Everything a compiled pipeline depends on, as a string (debug names excluded).
    static std::string reuseKey(const GraphicsPipelineDesc& desc, uint32_t textureCount);
    static std::string reuseKey(const ComputePipelineDesc& desc, uint32_t textureCount);
    void collectPipelineBuilds();
    void loadPipelineCache();
    void savePipelineCache();
};

template <typename Record>
void Device::Impl::immediate(Record&& record) {
    VkCommandBuffer commandBuffer = beginImmediate();
    record(commandBuffer);
    endImmediate(commandBuffer);
}

VkFormat toVkFormat(Format format);
VkCompareOp toVkCompareOp(CompareOp op);
bool isDepthFormat(Format format);
uint32_t bytesPerPixel(Format format);
// One layout transition of mip level `level` (count 1) of a colour image.
void recordColorImageBarrier(VkCommandBuffer commandBuffer, VkImage image, uint32_t level, VkImageLayout from,
                             VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                             VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// A global memory barrier.
void recordMemoryBarrier(VkCommandBuffer commandBuffer, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                         VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace penumbra::gpu
