#pragma once
// A Vulkan device for Penumbra: one of the machine's (a GPU, or lavapipe on a machine without one),
// or the caller's own VkDevice (see <penumbra/vulkan.h>). Renderers render on it. No Vulkan header
// is needed to use this one.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

namespace gpu {
class Device;
}

struct DeviceOptions {
    std::string device = "auto";  // auto | gpu | cpu | N (index in `penumbra devices` order)
    bool validation = false;      // Khronos validation layer + debug messenger; messages are counted
    // With validation: the layer's synchronization validation too (a missing or too narrow barrier
    // between two commands is a message). Slower; the synchronization render tests turn it on.
    bool synchronizationValidation = false;
    bool timestamps = true;       // GPU timestamps per pass
    uint32_t framesInFlight = 2;  // frames the CPU may record ahead of the GPU (1..4)
    // Wait for the GPU by polling its fences and semaphores instead of sleeping in the driver: the waiting
    // core never idles, so the CPU phases after a wait do not pay for its wake-up and lowered clock
    // (docs/performance.md, "Waiting for the GPU": their p95 went from 1.6-1.7x to 1.1x the median), at
    // the cost of that core's time while the GPU works.
    bool spinWait = false;
    // Folder of the persistent VkPipelineCache: "auto" = $XDG_CACHE_HOME/penumbra (else
    // ~/.cache/penumbra), "off" = none, else the folder to use.
    std::string pipelineCache = "auto";
};

struct DeviceInfo {
    std::string name;
    std::string driver;
    bool isCpu = false;
    uint32_t index = 0;
};

// A caller's Vulkan objects as integers (VkInstance, VkPhysicalDevice, VkDevice, VkQueue);
// <penumbra/vulkan.h> builds this from the Vulkan types.
struct ExternalVulkanDevice {
    uint64_t instance = 0, physicalDevice = 0, device = 0, queue = 0;
    uint32_t queueFamily = 0;
    // Optional features the caller enabled: shaderInt64 (1.0) and shaderBufferInt64Atomics (1.2) let
    // render.mainView use the visibility buffer; without them it draws forward.
    bool bufferInt64Atomics = false;
    // The timelineSemaphore feature (1.2): ShadowSystem's frames, recorded into the caller's command
    // buffers, complete on a timeline semaphore value that the caller's submission signals.
    bool timelineSemaphores = false;
    // The shaderStorageImageExtendedFormats feature (1.0): the virtual shadow maps' pools take 2 bytes a
    // texel (R16_UNORM) instead of 4.
    bool storageImageExtendedFormats = false;
};

// What is alive on a device, and what it has done so far (see Device::liveObjects).
struct DeviceObjectCounts {
    uint32_t buffers = 0, textures = 0, samplers = 0, pipelines = 0, textureTables = 0;
    uint32_t memoryBlocks = 0;      // VkDeviceMemory objects alive
    uint64_t memoryBlockBytes = 0;  // bytes held in those blocks
    uint64_t memoryUsedBytes = 0;   // bytes suballocated from them
    uint32_t pendingDestroys = 0;   // destroyed objects the GPU may still be using
    uint64_t memoryAllocations = 0; // vkAllocateMemory calls so far
    uint64_t objectsCreated = 0;    // buffers, textures, samplers, pipelines and texture tables so far
    uint64_t submits = 0;           // queue submissions so far
    uint64_t deviceWaits = 0;       // queue- or device-wide waits so far
    uint64_t debugNamesSet = 0;     // objects named for RenderDoc / Nsight (VK_EXT_debug_utils) so far
    // Pipelines compiled so far, and those created from a compiled pipeline that an earlier (destroyed)
    // pipeline of the same description left behind; the kept ones are not counted as live.
    uint64_t pipelinesCompiled = 0, pipelinesReused = 0;
    uint32_t pipelinesParked = 0;   // compiled pipelines kept for reuse now
    std::array<char, 48> lastObjectName{};  // the debug name of the last object made (truncated), "" if none
    uint32_t total() const {
        return buffers + textures + samplers + pipelines + textureTables + memoryBlocks + pendingDestroys;
    }
};

class Device {
public:
    // Throws penumbra::Error with one line when no device fits the choice.
    explicit Device(const DeviceOptions& options = {});
    Device(const ExternalVulkanDevice& external, const DeviceOptions& options = {});
    ~Device();
    Device(Device&&) noexcept;
    Device& operator=(Device&&) noexcept;

    const DeviceInfo& info() const;
    static std::vector<DeviceInfo> list();

    uint32_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;
    DeviceObjectCounts liveObjects() const;
    uint64_t deviceMemoryBytes() const;  // VK_EXT_memory_budget usage, else the allocator's blocks
    uint32_t maxImageSize() const;       // maxImageDimension2D: the largest texture, atlas or output side
    // True once a submission or a wait returned VK_ERROR_DEVICE_LOST: every later frame throws
    // penumbra::Error; destroy the renderers and this device, then make a new one.
    bool lost() const;
    void waitIdle();
    // The frame graph (docs/architecture.md): with recording on, each frame keeps its declared passes,
    // and frameGraphText prints the last frame's passes, their dependencies and barriers as
    // format "mermaid" or "dot" (penumbra graph). Off by default: recording costs CPU time per pass.
    void recordFrameGraph(bool on);
    std::string frameGraphText(const std::string& format) const;

private:
    friend struct DeviceAccess;  // the library's own layers (src/gpu/device_access.h)
    explicit Device(std::unique_ptr<gpu::Device> device);
    std::unique_ptr<gpu::Device> device_;
};

}  // namespace penumbra
