// The installed shadow sampling (include/penumbra/shadows.glsl): an engine's shader that includes it
// reads exactly the descriptors <penumbra/shadows/bindings.h> documents, where the includer's set and
// binding base put them; and Penumbra's own lit pass and resolves read the same descriptors (one source).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <penumbra/files.h>
#include <penumbra/shadows/bindings.h>

#include "gpu/shader_interface.h"
#include "pass_bindings.h"

namespace penumbra {
namespace {

std::vector<uint32_t> readSpirv(const std::string& name) {
    const std::vector<uint8_t> bytes = readFileBytes(std::string(PENUMBRA_TEST_SPIRV_DIR) + "/" + name + ".spv");
    std::vector<uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), words.size() * 4);
    return words;
}

gpu::DescriptorType gpuType(ShadowDescriptorType type) {
    switch (type) {
    case ShadowDescriptorType::UniformBuffer: return gpu::DescriptorType::UniformBuffer;
    case ShadowDescriptorType::StorageBuffer: return gpu::DescriptorType::StorageBuffer;
    case ShadowDescriptorType::CombinedImageSampler: break;
    }
    return gpu::DescriptorType::SampledTexture;
}

const gpu::ShaderResource* findResource(const gpu::ShaderInterface& shader, uint32_t set, uint32_t binding) {
    for (const gpu::ShaderResource& resource : shader.resources)
        if (resource.set == set && resource.binding == binding) return &resource;
    return nullptr;
}

// Every documented descriptor at set `set`, binding base + its binding, with its type and GLSL name;
// `skipLights`: a shader that samples by shadow slot and never reads the light table.
void expectShadowDescriptors(const gpu::ShaderInterface& shader, uint32_t set, uint32_t base, bool skipLights = false) {
    for (const ShadowDescriptor& descriptor : kShadowDescriptors) {
        if (skipLights && descriptor.binding == kShadowBindingLights) continue;
        const gpu::ShaderResource* resource = findResource(shader, set, base + descriptor.binding);
        ASSERT_NE(resource, nullptr) << descriptor.glslName << " not at set " << set << ", binding " << base + descriptor.binding;
        EXPECT_EQ(resource->name, descriptor.glslName);
        EXPECT_EQ(resource->type, gpuType(descriptor.type)) << descriptor.glslName;
        EXPECT_EQ(resource->count, 1u) << descriptor.glslName;
    }
}

TEST(ShadowGlsl, TheDescriptorTableHoldsEveryBindingOnceInOrder) {
    for (uint32_t i = 0; i < kShadowBindingCount; ++i) EXPECT_EQ(kShadowDescriptors[i].binding, i);
}

TEST(ShadowGlsl, AnEnginesFragmentShaderReadsExactlyTheDocumentedDescriptorsInSetZero) {
    const gpu::ShaderInterface shader = gpu::reflectShaderInterface(readSpirv("shadow_caller.frag"), "shadow_caller.frag");
    expectShadowDescriptors(shader, 0, 0);
    EXPECT_EQ(shader.resources.size(), size_t(kShadowBindingCount));  // nothing undocumented
    EXPECT_EQ(shader.pushConstantSize, 0u);
}

TEST(ShadowGlsl, TheIncludersSetAndBindingBaseMoveEveryDescriptor) {
    const gpu::ShaderInterface shader =
        gpu::reflectShaderInterface(readSpirv("shadow_caller_moved.comp"), "shadow_caller_moved.comp");
    expectShadowDescriptors(shader, 2, 8);
    EXPECT_EQ(shader.resources.size(), size_t(kShadowBindingCount) + 2);  // + the shader's own two buffers
}

TEST(ShadowGlsl, PenumbrasLitPassReadsTheSameDescriptorsFromItsShadowBindingBase) {
    for (const char* name : {"lit.frag", "visibility_resolve.comp", "visibility_resolve.frag"}) {
        SCOPED_TRACE(name);
        expectShadowDescriptors(gpu::embeddedShaderInterface(name), gpu_data::kPassSet, gpu_data::kLitShadowBindingBase, true);
    }
}

}  // namespace
}  // namespace penumbra
