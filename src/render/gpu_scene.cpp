#include "render/gpu_scene.h"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>

#include "scene_structs.h"

namespace penumbra {

namespace {

gpu_data::MaterialData packMaterial(const Material& m) {
    gpu_data::MaterialData data{};
    data.baseColorFactor = m.baseColorFactor;
    data.params = glm::vec4(m.metallic, m.roughness, m.alphaCutoff, 0.0f);
    uint32_t bits = 0;
    if (m.unlit) bits |= gpu_data::kMaterialUnlit;
    if (m.doubleSided) bits |= gpu_data::kMaterialDoubleSided;
    if (m.receiveShadows) bits |= gpu_data::kMaterialReceiveShadows;
    data.flags = glm::uvec4(m.baseColorTexture >= 0 ? uint32_t(m.baseColorTexture) + 1 : 0u, bits,
                            uint32_t(m.alphaMode), uint32_t(m.shadows));
    return data;
}

gpu::AddressMode addressMode(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge: return gpu::AddressMode::ClampToEdge;
        case TextureWrap::MirroredRepeat: return gpu::AddressMode::MirroredRepeat;
        case TextureWrap::Repeat: break;
    }
    return gpu::AddressMode::Repeat;
}

gpu::Filter filter(TextureFilter f) { return f == TextureFilter::Nearest ? gpu::Filter::Nearest : gpu::Filter::Linear; }

}  // namespace

// The Vulkan sampler that applies scene/texture_sampler.h's rule: the hardware's texel addressing is
// that rule; mipmaps only when the glTF minFilter asks for them (maxLod 0 otherwise).
gpu::SamplerDesc samplerDesc(const TextureSampler& sampler) {
    gpu::SamplerDesc desc;
    desc.filter = filter(sampler.magFilter);
    desc.minFilter = filter(sampler.minFilter);
    desc.mipmaps = sampler.mipmaps != MipmapMode::None;
    desc.mipmapFilter = sampler.mipmaps == MipmapMode::Nearest ? gpu::Filter::Nearest : gpu::Filter::Linear;
    desc.addressMode = addressMode(sampler.wrapS);
    desc.addressModeV = addressMode(sampler.wrapT);
    return desc;
}

GpuScene::GpuScene(gpu::Device& device, const Scene& scene) {
    std::vector<gpu_data::VertexData> vertices;
    std::vector<uint32_t> indices;
    struct MeshRange { uint32_t firstIndex, indexCount; int32_t vertexOffset; };
    std::vector<MeshRange> ranges;
    for (const Mesh& mesh : scene.meshes) {
        ranges.push_back({uint32_t(indices.size()), uint32_t(mesh.indices.size()), int32_t(vertices.size())});
        for (const Vertex& v : mesh.vertices)
            vertices.push_back({glm::vec4(v.osPosition, v.uv.x), glm::vec4(v.osNormal, v.uv.y)});
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    }
    std::vector<gpu_data::InstanceData> instances;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes.at(instance.meshIndex);
        gpu_data::InstanceData data{};
        data.worldFromObject = instance.worldFromObject;
        data.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(instance.worldFromObject)));
        data.info = glm::uvec4(mesh.materialIndex, 0, 0, 0);
        instances.push_back(data);
        const MeshRange& r = ranges[instance.meshIndex];
        if (r.indexCount > 0) draws_.push_back({i, r.firstIndex, r.indexCount, r.vertexOffset, mesh.materialIndex});
    }
    std::vector<gpu_data::MaterialData> materials;
    for (const Material& m : scene.materials) materials.push_back(packMaterial(m));
    if (materials.empty()) materials.push_back(packMaterial(Material{}));

    using gpu::MemoryKind;
    vertices_ = device.createBuffer(vertices.size() * sizeof(vertices[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                    vertices.data(), "vertices");
    indices_ = device.createBuffer(indices.size() * sizeof(uint32_t), gpu::kBufferIndex | gpu::kBufferStorage,
                                   MemoryKind::DeviceLocal, indices.data(), "indices");
    instances_ = device.createBuffer(instances.size() * sizeof(instances[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                     instances.data(), "instances");
    materials_ = device.createBuffer(materials.size() * sizeof(materials[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                     materials.data(), "materials");

    // Base-colour textures (sRGB, full mip chain), each with its glTF sampler. An empty scene still gets
    // one white texel so the table is never empty.
    std::vector<gpu::TextureHandle> textures;
    std::vector<gpu::SamplerHandle> samplers;
    std::vector<std::pair<TextureSampler, gpu::SamplerHandle>> made;  // one VkSampler per distinct sampler
    auto upload = [&](const Image& rgba, const TextureSampler& sampler) {
        gpu::TextureDesc desc{rgba.width, rgba.height, gpu::Format::RGBA8Srgb, gpu::kTextureSampled, 0, "baseColor"};
        const gpu::TextureHandle texture = device.createTexture(desc);
        device.uploadTexture(texture, rgba.pixels);
        textures.push_back(texture);
        auto found = std::find_if(made.begin(), made.end(), [&](const auto& m) { return m.first == sampler; });
        if (found == made.end()) found = made.insert(made.end(), {sampler, device.createSampler(samplerDesc(sampler))});
        samplers.push_back(found->second);
    };
    for (const Texture& t : scene.textures) upload(t.rgba, t.sampler);
    if (textures.empty()) upload(Image(1, 1, 4, 255), TextureSampler{});
    textureTable_ = device.createTextureTable(textures, samplers);
}

}  // namespace penumbra
