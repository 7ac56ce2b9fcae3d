#include "gpu/shader_registry.h"

#include <string>
#include <utility>

#include "core/error.h"

namespace penumbra::gpu {

extern const std::pair<std::string_view, std::span<const uint32_t>> kEmbeddedShaders[];
extern const size_t kEmbeddedShaderCount;

std::span<const uint32_t> embeddedShader(std::string_view name) {
    for (size_t i = 0; i < kEmbeddedShaderCount; ++i)
        if (kEmbeddedShaders[i].first == name) return kEmbeddedShaders[i].second;
    throw Error("internal: no embedded shader named '" + std::string(name) + "'");
}

}  // namespace penumbra::gpu
