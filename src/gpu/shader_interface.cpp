#include "gpu/shader_interface.h"

#include <spirv_cross_c.h>

#include <map>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "gpu/shader_registry.h"

namespace penumbra::gpu {

namespace {

const char* typeName(DescriptorType type) {
    switch (type) {
        case DescriptorType::UniformBuffer: return "uniform buffer";
        case DescriptorType::StorageBuffer: return "storage buffer";
        case DescriptorType::SampledTexture: return "sampled texture";
        case DescriptorType::StorageTexture: return "storage texture";
    }
    return "?";
}

std::string stageNames(uint32_t stages) {
    std::string names;
    for (auto [bit, name] : {std::pair{kStageVertex, "vertex"}, std::pair{kStageFragment, "fragment"},
                             std::pair{kStageCompute, "compute"}})
        if (stages & bit) names += (names.empty() ? "" : "|") + std::string(name);
    return names.empty() ? "none" : names;
}

// The SPIRV-Cross context of one reflection; its last error names what it could not read.
struct Reflection {
    spvc_context context = nullptr;
    std::string shader;

    explicit Reflection(std::string_view name) : shader(name) {
        if (spvc_context_create(&context) != SPVC_SUCCESS) throw Error("SPIRV-Cross: no context");
    }
    ~Reflection() { spvc_context_destroy(context); }
    Reflection(const Reflection&) = delete;
    Reflection& operator=(const Reflection&) = delete;

    void check(spvc_result result) const {
        if (result != SPVC_SUCCESS)
            throw Error("shader '" + shader + "': SPIR-V reflection failed: " + spvc_context_get_last_error_string(context));
    }
};

std::span<const spvc_reflected_resource> resourcesOf(const Reflection& r, spvc_resources resources, spvc_resource_type type) {
    const spvc_reflected_resource* list = nullptr;
    size_t count = 0;
    r.check(spvc_resources_get_resource_list_for_type(resources, type, &list, &count));
    return {list, count};
}

}  // namespace

ShaderInterface reflectShaderInterface(std::span<const uint32_t> spirv, std::string_view shaderName) {
    Reflection r(shaderName);
    spvc_parsed_ir ir = nullptr;
    r.check(spvc_context_parse_spirv(r.context, spirv.data(), spirv.size(), &ir));
    spvc_compiler compiler = nullptr;
    r.check(spvc_context_create_compiler(r.context, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler));
    spvc_set active = nullptr;
    r.check(spvc_compiler_get_active_interface_variables(compiler, &active));
    spvc_resources resources = nullptr;
    r.check(spvc_compiler_create_shader_resources_for_active_variables(compiler, &resources, active));

    ShaderInterface result;
    for (auto [spvcType, type] : {std::pair{SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, DescriptorType::UniformBuffer},
                                  std::pair{SPVC_RESOURCE_TYPE_STORAGE_BUFFER, DescriptorType::StorageBuffer},
                                  std::pair{SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, DescriptorType::SampledTexture},
                                  std::pair{SPVC_RESOURCE_TYPE_STORAGE_IMAGE, DescriptorType::StorageTexture}}) {
        for (const spvc_reflected_resource& resource : resourcesOf(r, resources, spvcType)) {
            ShaderResource& out = result.resources.emplace_back();
            out.set = spvc_compiler_get_decoration(compiler, resource.id, SpvDecorationDescriptorSet);
            out.binding = spvc_compiler_get_decoration(compiler, resource.id, SpvDecorationBinding);
            out.type = type;
            out.name = resource.name;
            const spvc_type declared = spvc_compiler_get_type_handle(compiler, resource.type_id);
            for (unsigned dimension = 0; dimension < spvc_type_get_num_array_dimensions(declared); ++dimension)
                out.count *= spvc_type_get_array_dimension(declared, dimension);
        }
    }
    for (spvc_resource_type unsupported : {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS,
                                           SPVC_RESOURCE_TYPE_SUBPASS_INPUT, SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE})
        for (const spvc_reflected_resource& resource : resourcesOf(r, resources, unsupported))
            throw Error("shader '" + r.shader + "': " + resource.name + " is a descriptor kind the passes cannot declare");
    for (const spvc_reflected_resource& block : resourcesOf(r, resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT)) {
        size_t size = 0;
        r.check(spvc_compiler_get_declared_struct_size(compiler, spvc_compiler_get_type_handle(compiler, block.base_type_id),
                                                       &size));
        result.pushConstantSize = uint32_t(size);
    }
    return result;
}

const ShaderInterface& embeddedShaderInterface(std::string_view shaderName) {
    // Embedded shaders never change: each is reflected once per process (pipelines are created on
    // the render thread and, asynchronously, on the device's worker thread).
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<ShaderInterface>, std::less<>> cache;
    std::lock_guard lock(mutex);
    if (const auto found = cache.find(shaderName); found != cache.end()) return *found->second;
    auto reflected = std::make_unique<ShaderInterface>(reflectShaderInterface(embeddedShader(shaderName), shaderName));
    return *cache.emplace(std::string(shaderName), std::move(reflected)).first->second;
}

namespace {

[[noreturn]] void mismatch(std::string_view pass, std::string_view shader, uint32_t binding, std::string_view name,
                           const std::string& what) {
    throw Error("pass '" + std::string(pass) + "', shader '" + std::string(shader) + "', binding " +
                std::to_string(binding) + " (" + std::string(name) + "): " + what);
}

const BindingDesc* findBinding(std::span<const BindingDesc> bindings, uint32_t binding) {
    for (const BindingDesc& b : bindings)
        if (b.binding == binding) return &b;
    return nullptr;
}

bool stageUses(const ShaderInterface& shader, uint32_t binding) {
    for (const ShaderResource& r : shader.resources)
        if (r.set == kPassDescriptorSet && r.binding == binding) return true;
    return false;
}

void checkUsedBindings(std::string_view pass, const PipelineStage& stage, const ShaderInterface& shader,
                       std::span<const BindingDesc> bindings, bool textureTable) {
    for (const ShaderResource& used : shader.resources) {
        if (used.set == kTextureTableDescriptorSet) {
            if (!textureTable) mismatch(pass, stage.shader, used.binding, used.name, "set 1 is used but the pass has no texture table");
            continue;
        }
        if (used.set != kPassDescriptorSet) mismatch(pass, stage.shader, used.binding, used.name, "set " + std::to_string(used.set) + " is not set 0 or 1");
        const BindingDesc* declared = findBinding(bindings, used.binding);
        if (!declared) mismatch(pass, stage.shader, used.binding, used.name, "used by the shader but not declared by the pass");
        if (declared->type != used.type)
            mismatch(pass, stage.shader, used.binding, used.name,
                     std::string("declared as ") + typeName(declared->type) + ", the shader has a " + typeName(used.type));
        if (declared->count < used.count)
            mismatch(pass, stage.shader, used.binding, used.name,
                     "an array of " + std::to_string(used.count) + " in the shader, " + std::to_string(declared->count) +
                         " declared");
        if (!(declared->stages & stage.stage))
            mismatch(pass, stage.shader, used.binding, used.name,
                     "used by the " + stageNames(stage.stage) + " stage but declared for " + stageNames(declared->stages));
    }
}

}  // namespace

void checkPipelineInterface(std::string_view pass, std::span<const PipelineStage> stages,
                            std::span<const BindingDesc> bindings, uint32_t pushConstantSize, bool textureTable) {
    for (size_t i = 0; i < bindings.size(); ++i)
        if (findBinding(bindings.first(i), bindings[i].binding))
            mismatch(pass, stages.empty() ? "" : stages[0].shader, bindings[i].binding, bindings[i].name, "declared twice");
    for (const PipelineStage& stage : stages) {
        const ShaderInterface& shader = embeddedShaderInterface(stage.shader);
        checkUsedBindings(pass, stage, shader, bindings, textureTable);
        if (shader.pushConstantSize && shader.pushConstantSize != pushConstantSize)
            throw Error("pass '" + std::string(pass) + "', shader '" + stage.shader + "': push constants are " +
                        std::to_string(shader.pushConstantSize) + " bytes in the shader, " +
                        std::to_string(pushConstantSize) + " declared");
    }
    // Exact stage masks: a stage named for a binding that another stage of this pipeline reads
    // must read it too.
    for (const BindingDesc& b : bindings) {
        bool usedHere = false;
        for (const PipelineStage& stage : stages) usedHere |= stageUses(embeddedShaderInterface(stage.shader), b.binding);
        if (!usedHere) continue;
        for (const PipelineStage& stage : stages)
            if ((b.stages & stage.stage) && !stageUses(embeddedShaderInterface(stage.shader), b.binding))
                mismatch(pass, stage.shader, b.binding, b.name,
                         "declared for the " + stageNames(stage.stage) + " stage, which does not use it");
    }
}

}  // namespace penumbra::gpu
