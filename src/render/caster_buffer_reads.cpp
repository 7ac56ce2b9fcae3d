// ShadowSystem's one read of an engine's caster buffers (penumbra/caster_buffers.h): the position, uv and
// index streams and the alpha textures copied to host memory, unpacked, and made a Scene.
#include "render/caster_buffer_reads.h"

#include <cstring>

#include "core/error.h"

namespace penumbra {

namespace {

// `count` values of type Vec (tightly packed floats) at offset + i x stride of the caller's buffer.
template <typename Vec>
std::vector<Vec> readStream(gpu::Device& device, uint64_t vkBuffer, uint64_t offset, uint32_t stride, uint32_t count) {
    std::vector<Vec> values(count);
    if (count == 0) return values;
    const uint64_t bytes = uint64_t(count - 1) * stride + sizeof(Vec);
    const std::vector<uint8_t> raw = device.readExternalBuffer(vkBuffer, offset, bytes);
    for (uint32_t i = 0; i < count; ++i) std::memcpy(&values[i], raw.data() + uint64_t(i) * stride, sizeof(Vec));
    return values;
}

std::vector<uint32_t> readIndices(gpu::Device& device, const CasterBuffers& casters) {
    std::vector<uint32_t> indices(casters.indexCount);
    const bool narrow = casters.indexType == CasterIndexType::Uint16;
    const std::vector<uint8_t> raw =
        device.readExternalBuffer(casters.vkIndexBuffer, casters.indexOffset, uint64_t(casters.indexCount) * (narrow ? 2 : 4));
    for (uint32_t i = 0; i < casters.indexCount; ++i) {
        if (narrow) {
            uint16_t value = 0;
            std::memcpy(&value, raw.data() + 2 * size_t(i), 2);
            indices[i] = value;
        } else {
            std::memcpy(&indices[i], raw.data() + 4 * size_t(i), 4);
        }
    }
    return indices;
}

}  // namespace

Scene readCasterBuffers(gpu::Device& device, const CasterBuffers& casters, std::vector<Light> lights) {
    validateCasterBuffers(casters);
    CasterBufferContents contents;
    contents.osPositions = readStream<glm::vec3>(device, casters.vkPositionBuffer, casters.positionOffset,
                                                 casters.positionStride, casters.vertexCount);
    if (casters.vkUvBuffer != 0)
        contents.uvs = readStream<glm::vec2>(device, casters.vkUvBuffer, casters.uvOffset, casters.uvStride, casters.vertexCount);
    contents.indices = readIndices(device, casters);
    for (const CasterTexture& texture : casters.alphaTextures) {
        Image rgba(texture.width, texture.height, 4);
        rgba.pixels = device.readExternalImageRgba8(texture.vkImage, texture.vkFormat, texture.width, texture.height,
                                                    texture.vkImageLayout);
        contents.alphaTextures.push_back(std::move(rgba));
    }
    return sceneFromCasterBuffers(casters, contents, std::move(lights));
}

}  // namespace penumbra
