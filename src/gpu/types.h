#pragma once
// The vocabulary of the thin GPU layer: handles, formats and descriptions. No Vulkan types here:
// render/ talks only in these terms, and src/gpu/*.cpp translates them (Godot RD / Filament backend
// style). Handles are indices into the Device's pools; 0 is never a valid handle.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra::gpu {

struct BufferHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct TextureHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct SamplerHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct PipelineHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct TextureTableHandle { uint32_t id = 0; explicit operator bool() const { return id != 0; } };

enum class Format { Undefined, RGBA8Unorm, RGBA8Srgb, R8Unorm, R32Float, R32Uint, RGBA16Float, D32Float };

enum BufferUsage : uint32_t {
    kBufferStorage = 1, kBufferUniform = 2, kBufferIndex = 4, kBufferTransferSrc = 8, kBufferTransferDst = 16,
};
enum class MemoryKind { DeviceLocal, HostVisible };

enum TextureUsage : uint32_t {
    kTextureSampled = 1, kTextureColorTarget = 2, kTextureDepthTarget = 4, kTextureStorage = 8,
    kTextureTransferSrc = 16, kTextureTransferDst = 32,
};

// Where a texture is in its life; the command list issues the barriers between states.
enum class TextureState { Undefined, ColorTarget, DepthTarget, ShaderRead, Storage, TransferSrc, TransferDst };

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

// Set 0 of every pipeline is pushed per draw (VK_KHR_push_descriptor); set 1 optionally holds a
// texture table (an array of sampled textures sized by specialization constant 0).
struct BindingDesc {
    uint32_t binding = 0;
    DescriptorType type = DescriptorType::StorageBuffer;
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
    std::vector<SpecConstant> specialization;
    std::string debugName;
};

struct DescriptorWrite {
    uint32_t binding = 0;
    BufferHandle buffer;
    TextureHandle texture;
    SamplerHandle sampler;
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
    std::vector<ColorAttachment> colors;
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

}  // namespace penumbra::gpu
