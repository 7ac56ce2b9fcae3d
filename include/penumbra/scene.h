#pragma once
// The loaded scene: plain data, flattened to world space. Produced by scene/gltf_loader and
// scene/demo_scene, consumed by shadows/ (planning), render/ (GPU) and reference/ (ray tracing).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <penumbra/image.h>

namespace penumbra {

// How a texture is sampled: glTF's sampler. src/scene/texture_sampler.h holds the texel rule that the
// GPU and the ray-traced reference both follow.
enum class TextureFilter { Nearest, Linear };
enum class MipmapMode { None, Nearest, Linear };  // None: level 0 only
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

struct TextureSampler {
    TextureFilter magFilter = TextureFilter::Linear;
    TextureFilter minFilter = TextureFilter::Linear;
    MipmapMode mipmaps = MipmapMode::Linear;  // glTF's default when no sampler or no minFilter is given
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    bool operator==(const TextureSampler&) const = default;
};

struct Vertex {
    glm::vec3 osPosition{0.0f};
    glm::vec3 osNormal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};
};

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
    void extend(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
    void extend(const Aabb& b) { if (b.valid()) { extend(b.min); extend(b.max); } }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }
    Aabb transformed(const glm::mat4& m) const;  // bounds of the 8 transformed corners
};

// One glTF primitive: triangles only, with its material.
struct Mesh {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // triangle list
    uint32_t materialIndex = 0;     // index into Scene::materials (a default material is always present)
    Aabb osBounds;
};

enum class AlphaMode { Opaque, Mask, Blend };
// How a material casts shadows (docs/scene-format.md's shadow modes): opaque, alpha-clipped, dithered, or none.
enum class MaterialShadowMode { On, Clip, Dither, Off };

struct Texture {
    Image rgba;  // RGBA8, sRGB-encoded colour
    std::string name;
    TextureSampler sampler;  // the glTF texture's sampler (filters, wrap modes)
};

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int baseColorTexture = -1;  // index into Scene::textures, -1 = none
    float metallic = 1.0f;
    float roughness = 1.0f;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    bool unlit = false;  // KHR_materials_unlit
    MaterialShadowMode shadows = MaterialShadowMode::On;
    bool receiveShadows = true;
};

// A mesh placed in the world: one per (node, primitive).
struct Instance {
    uint32_t meshIndex = 0;
    glm::mat4 worldFromObject{1.0f};
    bool castShadows = true;
    Aabb wsBounds;
    std::string nodeName;
};

enum class LightType { Directional, Spot, Point };
// Soft: the settings' filter; Hard: one bilinear 2x2 PCF tap; Pcss: contact-hardening soft shadows
// sized by shadowLightSize ("Percentage-Closer Soft Shadows", Fernando).
enum class LightShadows { None, Hard, Soft, Pcss };

struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;                     // lux (directional) or candela (spot, point)
    float range = 0.0f;                         // 0 = infinite (KHR_lights_punctual)
    float innerConeAngle = 0.0f;                // radians
    float outerConeAngle = 0.7853981634f;       // radians, pi/4 default
    glm::vec3 wsPosition{0.0f};
    glm::vec3 wsDirection{0.0f, 0.0f, -1.0f};   // the direction the light travels (node -Z), unit
    LightShadows shadows = LightShadows::Soft;
    float shadowStrength = 1.0f;
    float shadowBias = 0.0f;        // slope-scale depth bias
    float shadowNormalBias = 1.0f;  // in shadow texels
    float shadowNearPlane = 0.0f;   // near-plane offset (directional) or near clip (spot, point)
    // The emitter's size for pcss shadows: angular diameter in degrees (directional; the sun's 0.53) or
    // radius in metres (spot, point). The ray-traced reference's --soft samples the same disk.
    float shadowLightSize = 0.53f;
};

// shadowLightSize's default for a light type: 0.53° for the sun, a 5 cm emitter for spot and point lights.
inline float defaultShadowLightSize(LightType type) { return type == LightType::Directional ? 0.53f : 0.05f; }

struct Camera {
    std::string name;
    glm::mat4 worldFromView{1.0f};  // the camera node's world transform; the camera looks along -Z, +Y up
    float yfov = 0.8f;              // radians
    float zNear = 0.1f;
    float zFar = std::numeric_limits<float>::infinity();  // infinite when the glTF gives none
};

struct Scene {
    std::string sourcePath;  // "" for the built-in demo scene
    std::vector<Mesh> meshes;
    std::vector<Material> materials;  // never empty: index 0 may be the default material
    std::vector<Texture> textures;
    std::vector<Instance> instances;
    std::vector<Light> lights;  // in the order of the KHR_lights_punctual `lights` array
    std::optional<Camera> camera;  // node "camera", else the first camera (docs/scene-format.md)
    std::vector<Camera> cameras;   // every usable perspective camera of the glTF, in node order (the viewer's list)
    Aabb wsBounds;
    std::vector<std::string> warnings;  // one line each: things skipped while loading (e.g. line primitives)
};

}  // namespace penumbra
