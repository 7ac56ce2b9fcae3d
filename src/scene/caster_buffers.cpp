// An engine's caster buffers (penumbra/caster_buffers.h) as a Scene: their description checked, and the
// contents ShadowSystem read regrouped into one mesh per (mesh, material) pair.
#include "penumbra/caster_buffers.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/error.h"
#include "penumbra/scene_builder.h"

namespace penumbra {

namespace {

// The VkFormat values an alpha texture may have (vulkan_core.h): R8_UNORM, R8G8B8A8_UNORM / _SRGB,
// B8G8R8A8_UNORM / _SRGB.
bool supportedTextureFormat(uint32_t vkFormat) {
    return vkFormat == 9 || vkFormat == 37 || vkFormat == 43 || vkFormat == 44 || vkFormat == 50;
}

std::string instanceName(const CasterBuffers& casters, size_t i) {
    const std::string& name = casters.instances[i].name;
    return "caster instance " + std::to_string(i) + (name.empty() ? "" : " '" + name + "'");
}

void validateStreams(const CasterBuffers& c) {
    if (c.vkPositionBuffer == 0) throw Error("caster buffers: no position buffer (vkPositionBuffer)");
    if (c.vkIndexBuffer == 0) throw Error("caster buffers: no index buffer (vkIndexBuffer)");
    if (c.positionStride < 12 || c.positionStride % 4 != 0 || c.positionOffset % 4 != 0)
        throw Error("caster buffers: positionStride must be a multiple of 4 of at least 12 and positionOffset a multiple of 4, got " +
                    std::to_string(c.positionStride) + " and " + std::to_string(c.positionOffset));
    if (c.vkUvBuffer != 0 && (c.uvStride < 8 || c.uvStride % 4 != 0 || c.uvOffset % 4 != 0))
        throw Error("caster buffers: uvStride must be a multiple of 4 of at least 8 and uvOffset a multiple of 4, got " +
                    std::to_string(c.uvStride) + " and " + std::to_string(c.uvOffset));
    const uint64_t indexBytes = c.indexType == CasterIndexType::Uint16 ? 2 : 4;
    if (c.indexOffset % indexBytes != 0)
        throw Error("caster buffers: indexOffset " + std::to_string(c.indexOffset) + " is not a multiple of the index size " +
                    std::to_string(indexBytes));
}

void validateMeshes(const CasterBuffers& c) {
    for (size_t m = 0; m < c.meshes.size(); ++m) {
        const CasterMesh& mesh = c.meshes[m];
        if (mesh.indexCount % 3 != 0)
            throw Error("caster mesh " + std::to_string(m) + ": indexCount " + std::to_string(mesh.indexCount) +
                        " is not a whole number of triangles");
        if (uint64_t(mesh.firstIndex) + mesh.indexCount > c.indexCount)
            throw Error("caster mesh " + std::to_string(m) + ": indices " + std::to_string(mesh.firstIndex) + " + " +
                        std::to_string(mesh.indexCount) + " run past indexCount " + std::to_string(c.indexCount));
    }
}

void validateInstances(const CasterBuffers& c) {
    for (size_t i = 0; i < c.instances.size(); ++i) {
        const CasterInstance& instance = c.instances[i];
        if (instance.mesh >= c.meshes.size())
            throw Error(instanceName(c, i) + ": mesh " + std::to_string(instance.mesh) + " of " + std::to_string(c.meshes.size()));
        if (instance.alphaTexture >= int(c.alphaTextures.size()) || instance.alphaTexture < -1)
            throw Error(instanceName(c, i) + ": alphaTexture " + std::to_string(instance.alphaTexture) + " of " +
                        std::to_string(c.alphaTextures.size()));
        if (!std::isfinite(instance.alpha) || !std::isfinite(instance.alphaCutoff))
            throw Error(instanceName(c, i) + ": alpha and alphaCutoff must be finite");
        if (instance.alphaTexture >= 0 && c.vkUvBuffer == 0)
            throw Error(instanceName(c, i) + ": an alphaTexture needs texture coordinates (vkUvBuffer)");
    }
    for (size_t t = 0; t < c.alphaTextures.size(); ++t) {
        const CasterTexture& texture = c.alphaTextures[t];
        if (texture.vkImage == 0 || texture.width == 0 || texture.height == 0)
            throw Error("caster alpha texture " + std::to_string(t) + ": no image or an empty size");
        if (!supportedTextureFormat(texture.vkFormat))
            throw Error("caster alpha texture " + std::to_string(t) + ": VkFormat " + std::to_string(texture.vkFormat) +
                        " is not R8_UNORM, R8G8B8A8_UNORM/_SRGB or B8G8R8A8_UNORM/_SRGB");
    }
}

Material casterMaterial(const CasterInstance& instance) {
    Material material;
    material.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, instance.alpha);
    material.baseColorTexture = instance.alphaTexture;
    material.alphaCutoff = instance.alphaCutoff;
    material.shadows = instance.shadowMode;
    material.alphaMode = instance.alphaMode;
    material.doubleSided = instance.doubleSided;
    return material;
}

// The vertices mesh `m` uses, rebased to its own first vertex.
Mesh casterMesh(const CasterBuffers& c, const CasterBufferContents& contents, uint32_t m, uint32_t materialIndex) {
    const CasterMesh& range = c.meshes[m];
    Mesh mesh;
    mesh.name = "caster mesh " + std::to_string(m);
    mesh.materialIndex = materialIndex;
    if (range.indexCount == 0) return mesh;
    int64_t lowest = INT64_MAX, highest = INT64_MIN;
    for (uint32_t k = range.firstIndex; k < range.firstIndex + range.indexCount; ++k) {
        const int64_t vertex = int64_t(contents.indices[k]) + range.vertexOffset;
        lowest = std::min(lowest, vertex);
        highest = std::max(highest, vertex);
    }
    if (lowest < 0 || highest >= int64_t(c.vertexCount))
        throw Error("caster mesh " + std::to_string(m) + ": an index names vertex " +
                    std::to_string(lowest < 0 ? lowest : highest) + ", outside the " + std::to_string(c.vertexCount) +
                    " vertices of the streams");
    mesh.vertices.resize(size_t(highest - lowest + 1));
    for (int64_t v = lowest; v <= highest; ++v) {
        Vertex& vertex = mesh.vertices[size_t(v - lowest)];
        vertex.osPosition = contents.osPositions[size_t(v)];
        if (!contents.uvs.empty()) vertex.uv = contents.uvs[size_t(v)];
    }
    mesh.indices.reserve(range.indexCount);
    for (uint32_t k = range.firstIndex; k < range.firstIndex + range.indexCount; ++k)
        mesh.indices.push_back(uint32_t(int64_t(contents.indices[k]) + range.vertexOffset - lowest));
    return mesh;
}

}  // namespace

void validateCasterBuffers(const CasterBuffers& casters) {
    validateStreams(casters);
    validateMeshes(casters);
    validateInstances(casters);
}

Scene sceneFromCasterBuffers(const CasterBuffers& casters, const CasterBufferContents& contents, std::vector<Light> lights) {
    validateCasterBuffers(casters);
    if (contents.osPositions.size() != casters.vertexCount || contents.indices.size() != casters.indexCount ||
        (casters.vkUvBuffer != 0 && contents.uvs.size() != casters.vertexCount) ||
        contents.alphaTextures.size() != casters.alphaTextures.size())
        throw Error("internal: caster buffer contents do not match their description");
    SceneBuilder builder;
    for (size_t t = 0; t < contents.alphaTextures.size(); ++t)
        builder.addTexture({contents.alphaTextures[t], "caster alpha texture " + std::to_string(t), casters.alphaTextures[t].sampler});
    using MaterialKey = std::tuple<int, int, float, float, int, bool>;  // shadow and alpha modes, alpha, cutoff, texture, sides
    std::map<MaterialKey, uint32_t> materials;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> meshes;  // (caster mesh, material) -> scene mesh
    for (size_t i = 0; i < casters.instances.size(); ++i) {
        const CasterInstance& instance = casters.instances[i];
        const MaterialKey key{int(instance.shadowMode), int(instance.alphaMode), instance.alpha, instance.alphaCutoff,
                              instance.alphaTexture, instance.doubleSided};
        auto material = materials.find(key);
        if (material == materials.end()) material = materials.emplace(key, builder.addMaterial(casterMaterial(instance))).first;
        auto mesh = meshes.find({instance.mesh, material->second});
        if (mesh == meshes.end())
            mesh = meshes.emplace(std::pair{instance.mesh, material->second},
                                  builder.addMesh(casterMesh(casters, contents, instance.mesh, material->second))).first;
        builder.addInstance(mesh->second, instance.worldFromObject, instance.castShadows, instance.name);
    }
    for (Light& light : lights) builder.addLight(light);
    Scene scene = builder.build();
    scene.sourcePath = "";
    return scene;
}

}  // namespace penumbra
