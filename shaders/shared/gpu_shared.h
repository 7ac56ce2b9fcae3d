// Included by C++ and GLSL alike: lets one struct definition serve both (niagara's config.h idea).
// Small functions written in the common subset of both languages (PENUMBRA_INLINE) serve both too.
// Members come in 16-byte groups: vec4 / uvec4 / mat4, four 4-byte scalars, two vec2, or a vec3 and one
// scalar (a vec3 takes the first 12 bytes of a 16-byte slot, as std140 and std430 place it), so std140
// and std430 layouts equal the C++ layout; each C++
// struct gets static_asserts on size and offsets next to its definition.
#ifndef PENUMBRA_GPU_SHARED_H
#define PENUMBRA_GPU_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#define PENUMBRA_GPU_NAMESPACE_BEGIN namespace penumbra::gpu_data { \
    using vec2 = glm::vec2; using vec3 = glm::vec3; using vec4 = glm::vec4; using uvec4 = glm::uvec4; using ivec4 = glm::ivec4; using mat4 = glm::mat4; using uint = uint32_t; \
    using mat3 = glm::mat3;
#define PENUMBRA_GPU_NAMESPACE_END }
#define PENUMBRA_CONST(type, name, value) inline constexpr type name = value;
#define PENUMBRA_CHECK_LAYOUT(type, member, offset) static_assert(offsetof(type, member) == (offset), #type "." #member " offset");
#define PENUMBRA_CHECK_SIZE(type, size) static_assert(sizeof(type) == (size), "sizeof(" #type ")");
#define PENUMBRA_INLINE inline
#else
#define PENUMBRA_GPU_NAMESPACE_BEGIN
#define PENUMBRA_GPU_NAMESPACE_END
#define PENUMBRA_CONST(type, name, value) const type name = value;
#define PENUMBRA_CHECK_LAYOUT(type, member, offset)
#define PENUMBRA_CHECK_SIZE(type, size)
#define PENUMBRA_INLINE
#endif

#endif
