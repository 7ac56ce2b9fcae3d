// The descriptors that <penumbra/shadows.glsl> reads, for C++ and GLSL alike: binding numbers within
// its descriptor set, relative to PENUMBRA_SHADOW_BINDING_BASE (0 unless the including shader says
// otherwise), and in C++ the table an engine builds its VkDescriptorSetLayout from. Penumbra's own lit
// pass reads the same descriptors at its own base (docs/engine-integration.md).
#ifndef PENUMBRA_SHADOWS_BINDINGS_H
#define PENUMBRA_SHADOWS_BINDINGS_H

#ifdef __cplusplus
#include <cstdint>
#define PENUMBRA_SHADOW_BINDING(name, value) inline constexpr uint32_t name = value;
namespace penumbra {
#else
#define PENUMBRA_SHADOW_BINDING(name, value) const uint name = value;
#endif

PENUMBRA_SHADOW_BINDING(kShadowBindingView, 0u)                // uniform ShadowViewData: the camera
PENUMBRA_SHADOW_BINDING(kShadowBindingLights, 1u)              // ShadowLightSlot[]: each light's kind and shadow slot
PENUMBRA_SHADOW_BINDING(kShadowBindingDirectional, 2u)         // uniform DirectionalShadowData: cascades, lights
PENUMBRA_SHADOW_BINDING(kShadowBindingDirectionalAtlas, 3u)    // sampler2D (R32F depth), nearest
PENUMBRA_SHADOW_BINDING(kShadowBindingOther, 4u)               // uniform OtherShadowData: spot and point lights
PENUMBRA_SHADOW_BINDING(kShadowBindingOtherAtlas, 5u)          // sampler2D (R32F depth), nearest
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtual, 6u)             // uniform VirtualDirectionalShadowData
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtualPool, 7u)         // sampler2D (16-bit depth codes), nearest
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtualPages, 8u)        // VirtualPageEntry[]: the page tables
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtualFaces, 9u)        // uniform VirtualFaceShadowData
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtualFacePool, 10u)    // sampler2D (16-bit depth codes), nearest
PENUMBRA_SHADOW_BINDING(kShadowBindingVirtualFacePages, 11u)   // VirtualPageEntry[]: the faces' page table
PENUMBRA_SHADOW_BINDING(kShadowBindingCount, 12u)

#undef PENUMBRA_SHADOW_BINDING

#ifdef __cplusplus
enum class ShadowDescriptorType : uint32_t { UniformBuffer, StorageBuffer, CombinedImageSampler };

// One descriptor of <penumbra/shadows.glsl>: its binding (plus the includer's base), its type and the
// GLSL name of its block or sampler (what a shader reflection reports). Every stage that calls
// penumbraShadow reads all of them; the array holds them in binding order.
struct ShadowDescriptor {
    uint32_t binding;
    ShadowDescriptorType type;
    const char* glslName;
};

inline constexpr ShadowDescriptor kShadowDescriptors[kShadowBindingCount] = {
    {kShadowBindingView, ShadowDescriptorType::UniformBuffer, "PenumbraShadowViewBlock"},
    {kShadowBindingLights, ShadowDescriptorType::StorageBuffer, "PenumbraShadowLightBlock"},
    {kShadowBindingDirectional, ShadowDescriptorType::UniformBuffer, "DirectionalShadowBlock"},
    {kShadowBindingDirectionalAtlas, ShadowDescriptorType::CombinedImageSampler, "directionalShadowAtlas"},
    {kShadowBindingOther, ShadowDescriptorType::UniformBuffer, "OtherShadowBlock"},
    {kShadowBindingOtherAtlas, ShadowDescriptorType::CombinedImageSampler, "otherShadowAtlas"},
    {kShadowBindingVirtual, ShadowDescriptorType::UniformBuffer, "VirtualShadowBlock"},
    {kShadowBindingVirtualPool, ShadowDescriptorType::CombinedImageSampler, "virtualShadowPool"},
    {kShadowBindingVirtualPages, ShadowDescriptorType::StorageBuffer, "VirtualPageBlock"},
    {kShadowBindingVirtualFaces, ShadowDescriptorType::UniformBuffer, "VirtualFaceBlock"},
    {kShadowBindingVirtualFacePool, ShadowDescriptorType::CombinedImageSampler, "virtualFacePool"},
    {kShadowBindingVirtualFacePages, ShadowDescriptorType::StorageBuffer, "VirtualFacePageBlock"},
};
}  // namespace penumbra
#endif

#endif
