#pragma once
// The SPIR-V of every shader in shaders/, compiled by glslc at build time and embedded in the binary
// (cmake/shaders.cmake generates the table).
#include <cstdint>
#include <span>
#include <string_view>

namespace penumbra::gpu {

// Throws penumbra::Error when no shader has this name (e.g. "mesh.vert").
std::span<const uint32_t> embeddedShader(std::string_view name);

}  // namespace penumbra::gpu
