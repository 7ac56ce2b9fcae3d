#pragma once
// The vocabulary of the thin GPU layer: handles, formats and descriptions. No Vulkan types here:
// render/ talks only in these terms, and src/gpu/*.cpp translates them (Godot RD / Filament backend
// style). A handle's id is a slot of the Device's pools plus that slot's generation (gpu/handle_pool.h),
// so a handle kept past its object's destruction is caught when used; 0 is never a valid handle.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "penumbra/device.h"

namespace penumbra::gpu {

struct BufferHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct TextureHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct SamplerHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct PipelineHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct TextureTableHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };

enum class Format { Undefined, RGBA8Unorm, RGBA8Srgb, R8Unorm, R16Unorm, R32Float, R32Uint, RGBA16Float, D32Float };

enum BufferUsage : uint32_t {
    kBufferStorage = 1, kBufferUniform = 2, kBufferIndex = 4, kBufferTransferSrc = 8, kBufferTransferDst = 16,
    kBufferIndirect = 32,
};
enum class MemoryKind { DeviceLocal, HostVisible };

enum TextureUsage : uint32_t {
    kTextureSampled = 1, kTextureColorTarget = 2, kTextureDepthTarget = 4, kTextureStorage = 8,
    kTextureTransferSrc = 16, kTextureTransferDst = 32,
};

enum class Filter { Nearest, Linear };
enum class AddressMode { Repeat, ClampToEdge, ClampToBorderWhite, MirroredRepeat };
enum class CompareOp { Never, Less, LessOrEqual, Greater, GreaterOrEqual, Always };
enum class CullMode { None, Back };
enum class BlendMode { Opaque, Alpha };
enum class DescriptorType { UniformBuffer, StorageBuffer, SampledTexture /* combined with a sampler */, StorageTexture };

struct TextureDesc {
    uint32_t width = 1, height = 1;
    Format format = Format::RGBA8Unorm;
    uint32_t usage = kTextureSampled;
    uint32_t mipLevels = 1;  // 0 = full chain
    std::string debugName;
};

struct SamplerDesc {
    Filter filter = Filter::Linear;
    bool mipmaps = false;
    AddressMode addressMode = AddressMode::Repeat;
    bool compare = false;  // depth comparison sampler (hardware PCF)
    CompareOp compareOp = CompareOp::LessOrEqual;
    // glTF samplers set these apart; unset = `filter` (min and between mip levels) / `addressMode` (V).
    std::optional<Filter> minFilter;
    std::optional<Filter> mipmapFilter;
    std::optional<AddressMode> addressModeV;
};

// Shader stages, as a mask: which stages of a pipeline read a binding.
enum ShaderStage : uint32_t { kStageVertex = 1, kStageFragment = 2, kStageCompute = 4 };

// The descriptor sets of every pipeline: the pass's bindings (pushed), then the texture table.
inline constexpr uint32_t kPassDescriptorSet = 0;
inline constexpr uint32_t kTextureTableDescriptorSet = 1;

// Set 0 of every pipeline is pushed per draw (VK_KHR_push_descriptor); set 1 optionally holds a
// texture table (an array of sampled textures sized by specialization constant 0). Each pass declares
// its set 0 once (render/pass_layouts.h, numbers from shaders/shared/pass_bindings.h); pipeline
// creation checks the declaration against the shaders' SPIR-V (gpu/shader_interface.h).
struct BindingDesc {
    std::string name;  // the GLSL block or sampler it stands for, for error messages
    uint32_t binding = 0;
    DescriptorType type = DescriptorType::StorageBuffer;
    uint32_t stages = 0;  // ShaderStage bits: exactly the stages that read it
    uint32_t count = 1;   // descriptors in the binding: > 1 for an array (at least the shader's array size)
};

struct SpecConstant {
    uint32_t id = 0;
    uint32_t value = 0;
};

struct GraphicsPipelineDesc {
    std::string vertexShader;    // embedded shader name, e.g. "mesh.vert"
    std::string fragmentShader;  // empty: depth-only
    std::vector<BindingDesc> bindings;
    uint32_t pushConstantSize = 0;
    TextureTableHandle textureTable;  // optional set 1
    std::vector<Format> colorFormats;
    Format depthFormat = Format::Undefined;
    bool depthTest = true;
    bool depthWrite = true;
    CompareOp depthCompare = CompareOp::GreaterOrEqual;  // reversed-Z camera
    bool depthClamp = false;
    bool dynamicDepthBias = false;
    CullMode cullMode = CullMode::Back;
    BlendMode blend = BlendMode::Opaque;
    std::vector<SpecConstant> specialization;
    std::string debugName;
};

struct ComputePipelineDesc {
    std::string shader;
    std::vector<BindingDesc> bindings;
    uint32_t pushConstantSize = 0;
    TextureTableHandle textureTable;  // optional set 1
    std::vector<SpecConstant> specialization;
    std::string debugName;
};

// The largest minUniformBufferOffsetAlignment / minStorageBufferOffsetAlignment Vulkan allows: every
// buffer range a descriptor binds starts at a multiple of it (CommandList::pushDescriptors checks), so
// an offset right on one device is right on all.
constexpr uint64_t kPortableBufferOffsetAlignment = 256;
// `bytes` rounded up to a multiple of it: the stride of blocks laid one after another in a buffer.
constexpr uint64_t portablyAligned(uint64_t bytes) {
    return (bytes + kPortableBufferOffsetAlignment - 1) / kPortableBufferOffsetAlignment * kPortableBufferOffsetAlignment;
}

// A range of a buffer: what a descriptor binds and what a copy reads. size 0 = to the end.
struct BufferSlice {
    BufferHandle buffer;
    uint64_t offset = 0;
    uint64_t size = 0;
};

// Per-frame memory from the frame's upload ring: host-visible, valid until the frame's fence signals.
struct FrameAllocation {
    BufferSlice slice;
    void* mapped = nullptr;
};

struct DescriptorWrite {
    uint32_t binding = 0;
    BufferHandle buffer;
    TextureHandle texture;
    SamplerHandle sampler;
    uint64_t offset = 0;  // buffer range bound (size 0 = whole buffer from offset)
    uint64_t size = 0;
    uint32_t arrayElement = 0;  // of an array binding (BindingDesc::count)

    DescriptorWrite() = default;
    DescriptorWrite(uint32_t b, BufferHandle buf, TextureHandle tex, SamplerHandle smp)
        : binding(b), buffer(buf), texture(tex), sampler(smp) {}
    DescriptorWrite(uint32_t b, const BufferSlice& slice)
        : binding(b), buffer(slice.buffer), offset(slice.offset), size(slice.size) {}
};

struct ColorAttachment {
    TextureHandle texture;
    bool clear = true;
    float clearColor[4] = {0, 0, 0, 0};
};

struct DepthAttachment {
    TextureHandle texture;
    bool clear = true;
    float clearDepth = 0.0f;
};

struct RenderingDesc {
    uint32_t width = 0, height = 0;
    std::span<const ColorAttachment> colors;  // read by beginRendering only (not kept)
    DepthAttachment depth;  // texture id 0 = none
};

struct Rect {
    int32_t x = 0, y = 0;
    uint32_t width = 0, height = 0;
};

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

// GPU objects alive on a Device and cumulative counts: the public DeviceObjectCounts.
using ObjectCounts = penumbra::DeviceObjectCounts;

// A finished frame as the GPU reports it: timestamps per pass and the submit-to-fence time.
struct CompletedFrame {
    uint64_t frameIndex = 0;
    std::vector<PassTiming> timings;
    double submitToFenceMilliseconds = 0.0;
    // The frame's command buffer on the GPU, first to last command, and when it ended on the
    // device's timestamp clock (differences of gpuEndMilliseconds between frames are the frame
    // period the GPU kept); 0 without timestamps.
    double gpuFrameMilliseconds = 0.0, gpuEndMilliseconds = 0.0;
    std::vector<uint8_t> readback;  // what Device::readBackAtFrameEnd asked for, in call order
};

// An image the caller owns on the caller's VkDevice (penumbra/vulkan.h fills this from Vulkan types;
// the values are Vulkan handles and enums as integers so this header stays free of Vulkan).
struct ExternalTarget {
    uint64_t image = 0;            // VkImage
    uint32_t format = 0;           // VkFormat
    uint32_t width = 0, height = 0;
    uint32_t initialLayout = 0;    // VkImageLayout the image is in when the frame starts
    uint32_t finalLayout = 0;      // VkImageLayout to leave it in
    uint64_t waitSemaphore = 0;    // VkSemaphore (binary) the frame waits on before writing, or 0
    uint64_t waitStageMask = 0;    // VkPipelineStageFlags2 of that wait
    uint64_t signalSemaphore = 0;  // VkSemaphore (binary) signalled when the image is written, or 0
};

}  // namespace penumbra::gpu
