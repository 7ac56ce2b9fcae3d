// Descriptor bindings shared by the scene shaders (set 0 is pushed per pass, set 1 is the texture table).
#ifndef PENUMBRA_BINDINGS_GLSL
#define PENUMBRA_BINDINGS_GLSL
#include "pass_bindings.h"
#include "scene_structs.h"
#include "penumbra/shadows/noise.glsl"  // interleavedGradientNoise: dithered casters

layout(constant_id = 0) const uint kTextureCount = 1;

layout(set = kPassSet, binding = kSceneBindingFrame, std140) uniform FrameBlock { FrameData frame; };
layout(set = kPassSet, binding = kSceneBindingVertices, std430) readonly buffer VertexBlock { VertexData vertices[]; };
layout(set = kPassSet, binding = kSceneBindingInstances, std430) readonly buffer InstanceBlock { InstanceData instances[]; };
layout(set = kPassSet, binding = kSceneBindingMaterials, std430) readonly buffer MaterialBlock { MaterialData materials[]; };
layout(set = kPassSet, binding = kSceneBindingLights, std430) readonly buffer LightBlock { LightData lights[]; };
layout(set = kTextureTableSet, binding = kTextureTableBinding) uniform sampler2D baseColorTextures[kTextureCount];

// Base colour (factor x texture) of a material at uv; alpha included.
vec4 materialBaseColor(MaterialData material, vec2 uv) {
    vec4 color = material.baseColorFactor;
    if (material.baseColorTexture != 0u) color *= texture(baseColorTextures[material.baseColorTexture - 1u], uv);
    return color;
}

// The mip level of a texture sampled with uv gradients dx, dy (uv change to the next texel / pixel in
// x and y): Vulkan's isotropic rule, log2 of the larger footprint in texels. The shadow casters use it
// in the hardware (from dFdx / dFdy) and in the compute rasterizer alike.
float textureLevel(uint texture, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(baseColorTextures[texture], 0));
    float rho = max(length(dx * size), length(dy * size));
    return log2(max(rho, 1e-20));
}

// Base colour (factor x texture) with an explicit level (textureLevel); alpha included.
vec4 materialBaseColorLod(MaterialData material, vec2 uv, float level) {
    vec4 color = material.baseColorFactor;
    if (material.baseColorTexture != 0u) color *= textureLod(baseColorTextures[material.baseColorTexture - 1u], uv, level);
    return color;
}
#endif
