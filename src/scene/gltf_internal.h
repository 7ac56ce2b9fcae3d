#pragma once
// Shared by the glTF loader's translation units; not part of the public API.
#include <optional>
#include <string>
#include <vector>

// Must match src/scene/tinygltf_impl.cpp: the implementation is compiled without stb_image(_write).
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#include <tiny_gltf.h>

#include "penumbra/scene.h"
#include "scene/load_budget.h"

namespace penumbra {
class AssetAccess;
}

namespace penumbra::gltf {

// ---- parsing (gltf_parse.cpp): the GLB header and the JSON's nesting checked first, then tinygltf,
// every external file read through `access` (nullptr: none is read, a reference is an Error) and every
// image decoded within the budgets. `warnings`: tinygltf's, on one line.
tinygltf::Model parseGltf(const uint8_t* data, size_t size, const AssetAccess* access, LoadBudget& budget,
                          std::string& warnings);

struct LoadContext {
    std::string path;
    const tinygltf::Model& model;
    Scene& scene;
    LoadBudget& budget;  // vertices and indices are charged as the primitives are converted

    // Throws penumbra::Error("<path>: <what>").
    [[noreturn]] void fail(const std::string& what) const;
    void warn(const std::string& what) const;
};

// "light 2 'Sun'" style names for error messages.
std::string describe(const char* kind, size_t index, const std::string& name);

// ---- accessors (gltf_accessors.cpp): bounds-checked reads, any component type
std::vector<glm::vec3> readVec3(const LoadContext& ctx, int accessorIndex, const std::string& what);
std::vector<glm::vec2> readVec2(const LoadContext& ctx, int accessorIndex, const std::string& what);
std::vector<uint32_t> readIndices(const LoadContext& ctx, int accessorIndex, const std::string& what);

// ---- meshes (gltf_meshes.cpp): nullopt for skipped (non-triangle) primitives
std::optional<Mesh> convertPrimitive(const LoadContext& ctx, size_t meshIndex, size_t primitiveIndex,
                                     uint32_t defaultMaterialIndex);

// ---- materials and textures (gltf_materials.cpp)
void convertTextures(const LoadContext& ctx);
void convertMaterials(const LoadContext& ctx);

// ---- lights (gltf_lights.cpp)
void convertLights(const LoadContext& ctx);
// Gives the light its node's world position and -Z axis; a directional or spot light whose node has a
// zero scale (no direction) is an error naming `object`.
void placeLight(const LoadContext& ctx, const std::string& object, Light& light, const glm::mat4& worldFromNode);
// The KHR_lights_punctual light index a node references, or -1.
int nodeLightIndex(const LoadContext& ctx, size_t nodeIndex);

// ---- extras (gltf_extras.cpp): nullopt when absent; Error naming object and key when invalid
std::optional<bool> extraBool(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                              const char* key);
std::optional<float> extraNumber(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                                 const char* key, float minValue, float maxValue);
// Returns the index of the value in `allowed`.
std::optional<size_t> extraEnum(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                                const char* key, const std::vector<std::string>& allowed);

}  // namespace penumbra::gltf
