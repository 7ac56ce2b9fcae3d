#pragma once
// The GPU device: instance and physical-device selection, resource pools, submission, readback,
// timestamps and validation. The only entry point render/ has to the GPU. Vulkan stays inside
// src/gpu/*.cpp.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/image.h"
#include "gpu/command_list.h"
#include "gpu/types.h"

namespace penumbra::gpu {

struct DeviceOptions {
    std::string device = "auto";  // auto | gpu | cpu | N (index in the enumeration order)
    bool validation = false;      // Khronos validation layer + debug messenger
    bool timestamps = true;
};

struct DeviceInfo {
    std::string name;
    std::string driver;
    bool isCpu = false;
    uint32_t index = 0;
};

class Device {
public:
    // Throws penumbra::Error("no Vulkan device ...") with one line when none fits the choice.
    explicit Device(const DeviceOptions& options);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    const DeviceInfo& info() const;
    static std::vector<DeviceInfo> listDevices();

    BufferHandle createBuffer(size_t size, uint32_t usage, MemoryKind memory, const void* initialData = nullptr,
                              const std::string& debugName = "");
    void writeBuffer(BufferHandle buffer, const void* data, size_t size, size_t offset = 0);  // HostVisible only
    void* mappedPointer(BufferHandle buffer);
    TextureHandle createTexture(const TextureDesc& desc);
    // Uploads level 0 (tightly packed RGBA8 / R8 ...) and builds the mip chain; leaves it ShaderRead.
    void uploadTexture(TextureHandle texture, std::span<const uint8_t> pixels);
    SamplerHandle createSampler(const SamplerDesc& desc);
    TextureTableHandle createTextureTable(std::span<const TextureHandle> textures, SamplerHandle sampler);
    // One sampler per texture (samplers.size() == textures.size()).
    TextureTableHandle createTextureTable(std::span<const TextureHandle> textures, std::span<const SamplerHandle> samplers);
    PipelineHandle createGraphicsPipeline(const GraphicsPipelineDesc& desc);
    PipelineHandle createComputePipeline(const ComputePipelineDesc& desc);
    void destroy(BufferHandle handle);
    void destroy(TextureHandle handle);

    CommandList beginCommands();
    // Submits, waits, and collects the command list's timers (see lastTimings()).
    void submitAndWait(CommandList& commands);
    const std::vector<PassTiming>& lastTimings() const;

    // Copies a texture (RGBA8 / R8 / R32Float / D32Float) to host memory; the texture must be in
    // `state` and is left there. Float formats come back as 4 bytes per pixel.
    Image readTexture(TextureHandle texture, TextureState state);

    // Validation messages (warnings and errors) seen so far; tests fail on any.
    uint32_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;

    struct Impl;
    Impl& impl() { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra::gpu
