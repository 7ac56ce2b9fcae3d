#pragma once
// An engine's own shadow casters, described by its GPU buffers: one position stream (and a texture
// coordinate stream for alpha-tested casters), one index buffer, meshes as ranges of it (as
// vkCmdDrawIndexed draws them) and instances placing them, each with its shadow mode. ShadowSystem
// (penumbra/shadow_system.h) reads them once, when it is created, into the meshlet-ordered copy that its
// culling and rasterizers need; the engine keeps its buffers. Vulkan handles are integers here.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <penumbra/image.h>
#include <penumbra/scene.h>

namespace penumbra {

enum class CasterIndexType { Uint16, Uint32 };

// Triangles firstIndex .. firstIndex + indexCount - 1 of the index buffer, each index plus vertexOffset
// naming a vertex of the streams (vkCmdDrawIndexed's firstIndex and vertexOffset).
struct CasterMesh {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
};

// A mesh placed in the world, with how it casts (the shadow modes of docs/scene-format.md: on, clip,
// dither, off). Clip drops texels whose alpha (alpha x the texture's alpha at the vertex uv) is below
// alphaCutoff; dither drops them with probability 1 - alpha. Instances keep their index: ShadowSystem's
// setInstance* take it.
struct CasterInstance {
    uint32_t mesh = 0;  // index into CasterBuffers::meshes
    glm::mat4 worldFromObject{1.0f};
    bool castShadows = true;
    MaterialShadowMode shadowMode = MaterialShadowMode::On;
    float alpha = 1.0f;
    float alphaCutoff = 0.5f;
    int alphaTexture = -1;  // index into CasterBuffers::alphaTextures, -1 = none
    // How the engine's view draws it, for the view depth Penumbra draws itself when the engine hands over
    // none (ShadowViewDepth): Mask alpha-tests it (alpha, alphaCutoff, alphaTexture as above), Blend
    // leaves it out, and single-sided instances lose their back faces.
    AlphaMode alphaMode = AlphaMode::Opaque;
    bool doubleSided = false;
    std::string name;
};

// A texture whose alpha an alpha-tested caster reads: level 0 of a 2D VkImage made with TRANSFER_SRC
// usage, of VK_FORMAT_R8G8B8A8_UNORM / _SRGB, B8G8R8A8_UNORM / _SRGB or R8_UNORM (the value is the
// alpha), in vkImageLayout when ShadowSystem is created (it is left so). Penumbra keeps its own copy
// with a mip chain, sampled as `sampler` says.
struct CasterTexture {
    uint64_t vkImage = 0;
    uint32_t vkFormat = 0;
    uint32_t width = 0, height = 0;
    uint32_t vkImageLayout = 0;
    TextureSampler sampler;
};

struct CasterBuffers {
    // Object-space positions: VK_FORMAT_R32G32B32_SFLOAT at positionOffset + vertex x positionStride
    // of a VkBuffer made with TRANSFER_SRC usage (an interleaved vertex buffer serves as it is).
    uint64_t vkPositionBuffer = 0;
    uint64_t positionOffset = 0;
    uint32_t positionStride = 12;
    // Texture coordinates (R32G32_SFLOAT, the same rule); needed only by instances with an alphaTexture.
    uint64_t vkUvBuffer = 0;
    uint64_t uvOffset = 0;
    uint32_t uvStride = 8;
    uint32_t vertexCount = 0;  // vertices the streams hold
    uint64_t vkIndexBuffer = 0;  // TRANSFER_SRC usage; triangle lists
    uint64_t indexOffset = 0;
    CasterIndexType indexType = CasterIndexType::Uint32;
    uint32_t indexCount = 0;  // indices the buffer holds from indexOffset
    std::vector<CasterMesh> meshes;
    std::vector<CasterInstance> instances;
    std::vector<CasterTexture> alphaTextures;
};

// Throws penumbra::Error (one line, naming the field) for a description that cannot be read: a missing
// buffer, a stride or offset off 4-byte alignment, a mesh outside the index buffer, an instance naming
// no mesh or texture, an alpha texture without a uv stream, an unsupported texture format.
void validateCasterBuffers(const CasterBuffers& casters);

// What the buffers held, tightly packed (ShadowSystem reads it): vertexCount positions (and uvs when
// there is a uv stream), indexCount indices widened to 32 bits, each alpha texture as RGBA8.
struct CasterBufferContents {
    std::vector<glm::vec3> osPositions;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;
    std::vector<Image> alphaTextures;
};

// The Scene the casters make, with `lights`: one mesh per distinct (mesh, material) pair of the
// instances, holding the vertices its triangles use, and instance i of the scene is instance i of
// `casters`. Throws penumbra::Error for an index naming a vertex outside the streams.
Scene sceneFromCasterBuffers(const CasterBuffers& casters, const CasterBufferContents& contents, std::vector<Light> lights);

}  // namespace penumbra
