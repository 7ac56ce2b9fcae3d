#include "scene/texture_sampler.h"
#include "penumbra/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "core/error.h"
#include "penumbra/files.h"

namespace penumbra {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t b0 = bytes[i];
        const uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u;
        const uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
        const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        out += kAlphabet[(triple >> 18) & 63];
        out += kAlphabet[(triple >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
    }
    return out;
}

json toJson(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

json toJson(const glm::mat4& m) {
    json values = json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) values.push_back(m[c][r]);  // column-major, as glTF
    return values;
}

// Accumulates the single binary buffer and its bufferViews / accessors.
class BufferWriter {
public:
    explicit BufferWriter(json& root) : root_(root) {
        root_["bufferViews"] = json::array();
        root_["accessors"] = json::array();
    }

    int addView(const void* data, size_t size, int target) {
        while (bytes_.size() % 4) bytes_.push_back(0);  // glTF: accessor data 4-byte aligned
        json view = {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", size}};
        if (target) view["target"] = target;
        const auto* p = static_cast<const uint8_t*>(data);
        bytes_.insert(bytes_.end(), p, p + size);
        root_["bufferViews"].push_back(view);
        return int(root_["bufferViews"].size() - 1);
    }

    int addAccessor(const void* data, size_t count, size_t elementSize, int componentType, const char* type,
                    int target, json extra = json::object()) {
        json accessor = {{"bufferView", addView(data, count * elementSize, target)},
                         {"componentType", componentType},
                         {"count", count},
                         {"type", type}};
        accessor.update(extra);
        root_["accessors"].push_back(accessor);
        return int(root_["accessors"].size() - 1);
    }

    std::vector<uint8_t>& bytes() { return bytes_; }

private:
    json& root_;
    std::vector<uint8_t> bytes_;
};

json writeMesh(const Mesh& mesh, BufferWriter& buffer) {
    json primitive = {{"mode", 4}, {"material", mesh.materialIndex}, {"attributes", json::object()}};
    if (!mesh.vertices.empty()) {
        std::vector<glm::vec3> positions, normals;
        std::vector<glm::vec2> uvs;
        Aabb bounds;
        for (const Vertex& v : mesh.vertices) {
            positions.push_back(v.osPosition);
            normals.push_back(v.osNormal);
            uvs.push_back(v.uv);
            bounds.extend(v.osPosition);
        }
        const json minMax = {{"min", toJson(bounds.min)}, {"max", toJson(bounds.max)}};  // required for POSITION
        json& attributes = primitive["attributes"];
        attributes["POSITION"] = buffer.addAccessor(positions.data(), positions.size(), 12, kFloat, "VEC3", kArrayBuffer, minMax);
        attributes["NORMAL"] = buffer.addAccessor(normals.data(), normals.size(), 12, kFloat, "VEC3", kArrayBuffer);
        attributes["TEXCOORD_0"] = buffer.addAccessor(uvs.data(), uvs.size(), 8, kFloat, "VEC2", kArrayBuffer);
        if (!mesh.indices.empty())
            primitive["indices"] = buffer.addAccessor(mesh.indices.data(), mesh.indices.size(), 4, kUnsignedInt,
                                                      "SCALAR", kElementArrayBuffer);
    }
    return {{"name", mesh.name}, {"primitives", json::array({primitive})}};
}

json writeMaterial(const Material& material) {
    static const char* kAlphaModes[] = {"OPAQUE", "MASK", "BLEND"};
    static const char* kShadowModes[] = {"on", "clip", "dither", "off"};
    const glm::vec4& c = material.baseColorFactor;
    json pbr = {{"baseColorFactor", {c.r, c.g, c.b, c.a}},
                {"metallicFactor", material.metallic},
                {"roughnessFactor", material.roughness}};
    if (material.baseColorTexture >= 0) pbr["baseColorTexture"] = {{"index", material.baseColorTexture}};
    json out = {{"name", material.name},
                {"pbrMetallicRoughness", pbr},
                {"alphaMode", kAlphaModes[int(material.alphaMode)]},
                {"doubleSided", material.doubleSided},
                {"extras", {{"shadows", kShadowModes[int(material.shadows)]}, {"receiveShadows", material.receiveShadows}}}};
    if (material.alphaMode == AlphaMode::Mask) out["alphaCutoff"] = material.alphaCutoff;
    if (material.unlit) out["extensions"] = {{"KHR_materials_unlit", json::object()}};
    return out;
}

json writeLight(const Light& light) {
    static const char* kTypes[] = {"directional", "spot", "point"};
    static const char* kShadows[] = {"none", "hard", "soft", "pcss"};
    json out = {{"name", light.name},
                {"type", kTypes[int(light.type)]},
                {"color", toJson(light.color)},
                {"intensity", light.intensity},
                {"extras",
                 {{"shadows", kShadows[int(light.shadows)]},
                  {"shadowStrength", light.shadowStrength},
                  {"shadowBias", light.shadowBias},
                  {"shadowNormalBias", light.shadowNormalBias},
                  {"shadowNearPlane", light.shadowNearPlane}}}};
    // Also an edited size without pcss (a later edit may pick pcss); a default one only with it.
    if (light.shadows == LightShadows::Pcss || light.shadowLightSize != defaultShadowLightSize(light.type))
        out["extras"]["shadowLightSize"] = light.shadowLightSize;
    if (light.range > 0.0f && light.type != LightType::Directional) out["range"] = light.range;
    if (light.type == LightType::Spot)
        out["spot"] = {{"innerConeAngle", light.innerConeAngle}, {"outerConeAngle", light.outerConeAngle}};
    return out;
}

// A rotation whose -Z axis is wsDirection (KHR_lights_punctual: lights shine along -Z).
glm::quat rotationForDirection(const glm::vec3& wsDirection) {
    const glm::vec3 z = -glm::normalize(wsDirection);
    const glm::vec3 up = std::abs(z.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::vec3 x = glm::normalize(glm::cross(up, z));
    const glm::vec3 y = glm::cross(z, x);
    return glm::normalize(glm::quat_cast(glm::mat3(x, y, z)));
}

json writeLightNode(const Light& light, size_t lightIndex) {
    const glm::quat r = rotationForDirection(light.wsDirection);
    return {{"name", light.name.empty() ? "light " + std::to_string(lightIndex) : light.name},
            {"translation", toJson(light.wsPosition)},
            {"rotation", {r.x, r.y, r.z, r.w}},  // glTF order (x, y, z, w)
            {"extensions", {{"KHR_lights_punctual", {{"light", lightIndex}}}}}};
}

json writeCamera(const Camera& camera) {
    json perspective = {{"yfov", camera.yfov}, {"znear", camera.zNear}};
    if (std::isfinite(camera.zFar)) perspective["zfar"] = camera.zFar;
    return {{"name", camera.name}, {"type", "perspective"}, {"perspective", perspective}};
}

void writeTextures(const Scene& scene, json& root, BufferWriter& buffer) {
    if (scene.textures.empty()) return;
    root["samplers"] = json::array();
    std::vector<TextureSampler> samplers;  // one glTF sampler per distinct TextureSampler
    root["images"] = json::array();
    root["textures"] = json::array();
    for (const Texture& texture : scene.textures) {
        const Image& image = texture.rgba;
        std::vector<uint8_t> png;
        const auto append = [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(context);
            out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
        };
        if (!stbi_write_png_to_func(append, &png, int(image.width), int(image.height), int(image.channels),
                                    image.pixels.data(), int(image.width * image.channels)))
            throw Error("cannot encode texture '" + texture.name + "' as PNG");
        const int view = buffer.addView(png.data(), png.size(), 0);
        root["images"].push_back({{"name", texture.name}, {"bufferView", view}, {"mimeType", "image/png"}});
        size_t sampler = 0;
        while (sampler < samplers.size() && !(samplers[sampler] == texture.sampler)) ++sampler;
        if (sampler == samplers.size()) {
            samplers.push_back(texture.sampler);
            root["samplers"].push_back({{"magFilter", gltfMagFilterCode(texture.sampler)},
                                        {"minFilter", gltfMinFilterCode(texture.sampler)},
                                        {"wrapS", gltfWrapCode(texture.sampler.wrapS)},
                                        {"wrapT", gltfWrapCode(texture.sampler.wrapT)}});
        }
        root["textures"].push_back({{"name", texture.name}, {"sampler", sampler}, {"source", root["images"].size() - 1}});
    }
}

void buildDocument(const Scene& scene, BufferWriter& buffer, json& root) {
    std::vector<std::string> extensionsUsed;
    json nodes = json::array();
    for (const Instance& instance : scene.instances)
        nodes.push_back({{"name", instance.nodeName}, {"mesh", instance.meshIndex},
                         {"matrix", toJson(instance.worldFromObject)}, {"extras", {{"castShadows", instance.castShadows}}}});
    root["meshes"] = json::array();
    for (const Mesh& mesh : scene.meshes) root["meshes"].push_back(writeMesh(mesh, buffer));
    writeTextures(scene, root, buffer);
    root["materials"] = json::array();
    for (const Material& material : scene.materials) {
        root["materials"].push_back(writeMaterial(material));
        if (material.unlit && extensionsUsed.empty()) extensionsUsed.push_back("KHR_materials_unlit");
    }
    if (!scene.lights.empty()) {
        json lights = json::array();
        for (size_t i = 0; i < scene.lights.size(); ++i) {
            lights.push_back(writeLight(scene.lights[i]));
            nodes.push_back(writeLightNode(scene.lights[i], i));
        }
        root["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
        extensionsUsed.push_back("KHR_lights_punctual");
    }
    if (scene.camera) {
        root["cameras"] = json::array({writeCamera(*scene.camera)});
        nodes.push_back({{"name", "camera"}, {"camera", 0}, {"matrix", toJson(scene.camera->worldFromView)}});
    }
    json sceneNodes = json::array();
    for (size_t i = 0; i < nodes.size(); ++i) sceneNodes.push_back(i);
    root["nodes"] = nodes;
    root["scenes"] = json::array({{{"nodes", sceneNodes}}});
    root["scene"] = 0;
    if (!extensionsUsed.empty()) root["extensionsUsed"] = extensionsUsed;
}

void appendU32(std::vector<uint8_t>& out, uint32_t value) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(value >> (8 * i)));  // little-endian
}

// GLB container: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros.
std::vector<uint8_t> makeGlb(std::string jsonText, std::vector<uint8_t> bin) {
    while (jsonText.size() % 4) jsonText += ' ';
    while (bin.size() % 4) bin.push_back(0);
    const size_t total = 12 + 8 + jsonText.size() + (bin.empty() ? 0 : 8 + bin.size());
    std::vector<uint8_t> out;
    out.reserve(total);
    appendU32(out, 0x46546C67);  // "glTF"
    appendU32(out, 2);
    appendU32(out, uint32_t(total));
    appendU32(out, uint32_t(jsonText.size()));
    appendU32(out, 0x4E4F534A);  // "JSON"
    out.insert(out.end(), jsonText.begin(), jsonText.end());
    if (!bin.empty()) {
        appendU32(out, uint32_t(bin.size()));
        appendU32(out, 0x004E4942);  // "BIN\0"
        out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
}

bool endsWith(std::string text, const std::string& suffix) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

void writeGltfScene(const Scene& scene, const std::string& path) {
    const bool binary = endsWith(path, ".glb");
    if (!binary && !endsWith(path, ".gltf")) throw Error(path + ": a glTF file name must end in .gltf or .glb");
    json root = {{"asset", {{"version", "2.0"}, {"generator", "penumbra"}}}};
    BufferWriter buffer(root);
    buildDocument(scene, buffer, root);
    std::vector<uint8_t>& bin = buffer.bytes();
    if (!bin.empty()) {
        json gltfBuffer = {{"byteLength", bin.size()}};
        if (!binary) gltfBuffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
        root["buffers"] = json::array({gltfBuffer});
    } else {
        root.erase("bufferViews");
        root.erase("accessors");
    }
    // Whole or not at all (temporary name, then rename): a failed export leaves no half file.
    if (binary) {
        const std::vector<uint8_t> glb = makeGlb(root.dump(), bin);
        writeFileAtomically(path, glb.data(), glb.size());
    } else {
        writeTextFile(path, root.dump(1));
    }
}

}  // namespace penumbra
