#pragma once
// What a pass declares about its shaders' set 0 and push constants (types.h BindingDesc), checked
// against what the SPIR-V says: every pipeline is checked when it is created, so a binding number,
// descriptor type, stage or push-constant size that C++ and GLSL disagree on is an Error naming the
// pass, the shader and the binding, not a validation message or a wrong image. The SPIR-V is
// reflected with SPIRV-Cross's C API, once per embedded shader.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/types.h"

namespace penumbra::gpu {

// A descriptor or push-constant block that a shader's entry point reads or writes.
struct ShaderResource {
    uint32_t set = 0;
    uint32_t binding = 0;
    DescriptorType type = DescriptorType::StorageBuffer;
    std::string name;  // the block's (or sampler's) name in the GLSL
    uint32_t count = 1;  // descriptors: an array's size (0: a runtime-sized array)
};

struct ShaderInterface {
    std::vector<ShaderResource> resources;  // only what the entry point uses
    uint32_t pushConstantSize = 0;          // 0: no push-constant block used
};

// Reflects SPIR-V words (throws Error, naming `shaderName`, for what the passes cannot declare:
// separate images or samplers, input attachments, ...).
ShaderInterface reflectShaderInterface(std::span<const uint32_t> spirv, std::string_view shaderName);

// The interface of an embedded shader (shader_registry.h), reflected on first use and kept.
const ShaderInterface& embeddedShaderInterface(std::string_view shaderName);

struct PipelineStage {
    ShaderStage stage = kStageCompute;
    std::string shader;  // embedded shader name, e.g. "mesh.vert"
};

// Throws Error("pass '<pass>', shader '<shader>', binding <n> (<name>): ...") when
// - a shader uses a set-0 binding the pass does not declare, or declares with another type, or
//   declares without that shader's stage;
// - a declared binding names a stage of this pipeline that does not use it while another stage
//   does (stage masks are exact; a binding no stage of this pipeline uses is allowed, as passes
//   share one declaration between their pipelines);
// - a binding is declared twice, or a shader uses set 1 without a texture table;
// - a shader's push-constant block is not pushConstantSize bytes.
void checkPipelineInterface(std::string_view pass, std::span<const PipelineStage> stages,
                            std::span<const BindingDesc> bindings, uint32_t pushConstantSize, bool textureTable);

}  // namespace penumbra::gpu
