// Bounds-checked accessor reads: every index, offset and length in the file is validated before a
// byte is touched, so a malformed file is an Error, never an out-of-bounds read.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "scene/gltf_internal.h"

namespace penumbra::gltf {
namespace {

struct AccessorData {
    const uint8_t* base = nullptr;  // the first element in the buffer
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int componentCount = 0;
    bool normalized = false;
};

int componentCountOf(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

size_t componentSizeOf(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

AccessorData checkedAccessor(const LoadContext& ctx, int accessorIndex, const std::string& what, int expectedCount) {
    const tinygltf::Model& model = ctx.model;
    if (accessorIndex < 0 || size_t(accessorIndex) >= model.accessors.size())
        ctx.fail(what + ": accessor " + std::to_string(accessorIndex) + " is out of range (the file has " +
                 std::to_string(model.accessors.size()) + ")");
    const tinygltf::Accessor& accessor = model.accessors[size_t(accessorIndex)];
    const std::string name = what + ": accessor " + std::to_string(accessorIndex);
    if (accessor.sparse.isSparse) ctx.fail(name + " is sparse, which is not supported");
    AccessorData data;
    data.count = accessor.count;
    data.componentType = accessor.componentType;
    data.componentCount = componentCountOf(accessor.type);
    data.normalized = accessor.normalized;
    const size_t componentSize = componentSizeOf(accessor.componentType);
    if (componentSize == 0) ctx.fail(name + " has an invalid componentType " + std::to_string(accessor.componentType));
    if (data.componentCount != expectedCount)
        ctx.fail(name + " has " + std::to_string(data.componentCount) + " components per element, expected " +
                 std::to_string(expectedCount));
    // glTF initializes an accessor without a bufferView to zeros, for sparse data to patch; without
    // sparse support such an accessor holds nothing useful, and its count alone could ask for gigabytes.
    if (accessor.bufferView < 0) ctx.fail(name + " has no bufferView (all-zero accessors are not supported)");
    if (size_t(accessor.bufferView) >= model.bufferViews.size())
        ctx.fail(name + " references bufferView " + std::to_string(accessor.bufferView) + ", out of range (the file has " +
                 std::to_string(model.bufferViews.size()) + ")");
    const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
    const std::string viewName = "bufferView " + std::to_string(accessor.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        ctx.fail(viewName + " references buffer " + std::to_string(view.buffer) + ", out of range (the file has " +
                 std::to_string(model.buffers.size()) + ")");
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    // Every sum below is done in 128 bits: offsets, strides and counts come from the file, and a wrapped
    // 64-bit sum would pass the checks.
    using u128 = unsigned __int128;
    const u128 viewEnd = u128(view.byteOffset) + view.byteLength;
    if (viewEnd > buffer.data.size())
        ctx.fail(viewName + " reads past the end of buffer " + std::to_string(view.buffer) + " (needs " +
                 std::to_string(uint64_t(std::min<u128>(viewEnd, UINT64_MAX))) + " bytes, has " +
                 std::to_string(buffer.data.size()) + ")");
    const size_t elementSize = componentSize * size_t(data.componentCount);
    data.stride = view.byteStride ? view.byteStride : elementSize;
    if (data.stride < elementSize) ctx.fail(viewName + " has a byteStride smaller than its elements");
    const u128 end = data.count == 0 ? u128(accessor.byteOffset)
                                     : u128(accessor.byteOffset) + u128(data.stride) * (data.count - 1) + elementSize;
    if (end > view.byteLength)
        ctx.fail(name + " reads past the end of its " + viewName + " (needs " +
                 std::to_string(uint64_t(std::min<u128>(end, UINT64_MAX))) + " bytes, has " +
                 std::to_string(view.byteLength) + ")");
    data.base = buffer.data.data() + view.byteOffset + accessor.byteOffset;
    return data;
}

template <typename T>
T load(const uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // unaligned-safe
    return value;
}

// One component as float, with glTF's normalization rules for integer types.
float readComponent(const AccessorData& data, const uint8_t* p) {
    switch (data.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return data.normalized ? load<uint8_t>(p) / 255.0f : load<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return data.normalized ? load<uint16_t>(p) / 65535.0f : load<uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return data.normalized ? std::max(load<int8_t>(p) / 127.0f, -1.0f) : load<int8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return data.normalized ? std::max(load<int16_t>(p) / 32767.0f, -1.0f) : load<int16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return float(load<uint32_t>(p));
        default: return 0.0f;
    }
}

template <int N>
std::vector<glm::vec<N, float>> readVectors(const LoadContext& ctx, int accessorIndex, const std::string& what) {
    const AccessorData data = checkedAccessor(ctx, accessorIndex, what, N);
    std::vector<glm::vec<N, float>> values(data.count, glm::vec<N, float>(0.0f));
    const size_t componentSize = componentSizeOf(data.componentType);
    for (size_t i = 0; i < data.count; ++i) {
        const uint8_t* element = data.base + i * data.stride;
        for (int c = 0; c < N; ++c) values[i][c] = readComponent(data, element + size_t(c) * componentSize);
    }
    return values;
}

}  // namespace

std::vector<glm::vec3> readVec3(const LoadContext& ctx, int accessorIndex, const std::string& what) {
    return readVectors<3>(ctx, accessorIndex, what);
}

std::vector<glm::vec2> readVec2(const LoadContext& ctx, int accessorIndex, const std::string& what) {
    return readVectors<2>(ctx, accessorIndex, what);
}

std::vector<uint32_t> readIndices(const LoadContext& ctx, int accessorIndex, const std::string& what) {
    const AccessorData data = checkedAccessor(ctx, accessorIndex, what, 1);
    std::vector<uint32_t> indices(data.count, 0u);
    for (size_t i = 0; i < data.count; ++i) {
        const uint8_t* p = data.base + i * data.stride;
        switch (data.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = load<uint8_t>(p); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: indices[i] = load<uint16_t>(p); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: indices[i] = load<uint32_t>(p); break;
            default:
                ctx.fail(what + ": accessor " + std::to_string(accessorIndex) +
                         " has a componentType not allowed for indices (" + std::to_string(data.componentType) + ")");
        }
    }
    return indices;
}

}  // namespace penumbra::gltf
