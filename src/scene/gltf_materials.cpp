// glTF textures and pbrMetallicRoughness materials with their shadow extras.
#include <cmath>

#include "core/error.h"
#include "scene/texture_sampler.h"
#include "scene/gltf_internal.h"
#include "scene/scene_validation.h"

namespace penumbra::gltf {
namespace {

TextureSampler convertSampler(const LoadContext& ctx, int index, const std::string& textureName) {
    TextureSampler sampler;
    if (index < 0) return sampler;  // glTF: no sampler = repeat wrapping, filtering left to us (linear, mipmapped)
    if (size_t(index) >= ctx.model.samplers.size())
        ctx.fail(textureName + ": sampler " + std::to_string(index) + " is out of range (the file has " +
                 std::to_string(ctx.model.samplers.size()) + ")");
    const tinygltf::Sampler& source = ctx.model.samplers[size_t(index)];
    const std::string object = describe("sampler", size_t(index), source.name);
    if (!setGltfMagFilter(sampler, source.magFilter))
        ctx.fail(object + ": magFilter " + std::to_string(source.magFilter) + " is not 9728 (NEAREST) or 9729 (LINEAR)");
    if (!setGltfMinFilter(sampler, source.minFilter))
        ctx.fail(object + ": minFilter " + std::to_string(source.minFilter) + " is not one of glTF's 9728, 9729, 9984-9987");
    if (!gltfWrap(source.wrapS, sampler.wrapS))
        ctx.fail(object + ": wrapS " + std::to_string(source.wrapS) + " is not 33071, 33648 or 10497");
    if (!gltfWrap(source.wrapT, sampler.wrapT))
        ctx.fail(object + ": wrapT " + std::to_string(source.wrapT) + " is not 33071, 33648 or 10497");
    return sampler;
}

Texture convertTexture(const LoadContext& ctx, size_t index) {
    const tinygltf::Texture& source = ctx.model.textures[index];
    const std::string object = describe("texture", index, source.name);
    if (source.source < 0 || size_t(source.source) >= ctx.model.images.size())
        ctx.fail(object + ": image " + std::to_string(source.source) + " is out of range (the file has " +
                 std::to_string(ctx.model.images.size()) + ")");
    const tinygltf::Image& image = ctx.model.images[size_t(source.source)];
    const std::string imageName = describe("image", size_t(source.source), image.uri.empty() ? image.name : image.uri);
    // The image loader callback decodes every image to RGBA8; anything else means it was not loaded.
    if (image.image.empty() || image.component != 4 || image.bits != 8 || image.width <= 0 || image.height <= 0 ||
        image.image.size() != size_t(image.width) * size_t(image.height) * 4)
        ctx.fail(object + ": " + imageName + " could not be loaded or decoded");
    Texture texture;
    texture.name = source.name.empty() ? image.name : source.name;
    texture.rgba.width = uint32_t(image.width);
    texture.rgba.height = uint32_t(image.height);
    texture.rgba.channels = 4;
    texture.rgba.pixels = image.image;
    texture.sampler = convertSampler(ctx, source.sampler, object);
    return texture;
}

void readShadowExtras(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                      Material& material) {
    // The defaults of docs/scene-format.md: OPAQUE casts solid shadows, MASK clips them, BLEND dithers them.
    switch (material.alphaMode) {
        case AlphaMode::Opaque: material.shadows = MaterialShadowMode::On; break;
        case AlphaMode::Mask: material.shadows = MaterialShadowMode::Clip; break;
        case AlphaMode::Blend: material.shadows = MaterialShadowMode::Dither; break;
    }
    if (auto mode = extraEnum(ctx, extras, object, "shadows", {"on", "clip", "dither", "off"}))
        material.shadows = MaterialShadowMode(*mode);
    if (auto receive = extraBool(ctx, extras, object, "receiveShadows")) material.receiveShadows = *receive;
}

Material convertMaterial(const LoadContext& ctx, size_t index) {
    const tinygltf::Material& source = ctx.model.materials[index];
    const std::string object = describe("material", index, source.name);
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    Material material;
    material.name = source.name;
    if (pbr.baseColorFactor.size() != 4) ctx.fail(object + ": baseColorFactor must have 4 components");
    for (int c = 0; c < 4; ++c) {
        material.baseColorFactor[c] = float(pbr.baseColorFactor[size_t(c)]);
        if (!std::isfinite(material.baseColorFactor[c])) ctx.fail(object + ": baseColorFactor must be finite");
    }
    if (pbr.baseColorTexture.index >= 0) {
        if (size_t(pbr.baseColorTexture.index) >= ctx.scene.textures.size())
            ctx.fail(object + ": baseColorTexture " + std::to_string(pbr.baseColorTexture.index) +
                     " is out of range (the file has " + std::to_string(ctx.scene.textures.size()) + " textures)");
        material.baseColorTexture = pbr.baseColorTexture.index;
        if (pbr.baseColorTexture.texCoord != 0)
            ctx.warn(object + ": baseColorTexture uses TEXCOORD_" + std::to_string(pbr.baseColorTexture.texCoord) +
                     "; only TEXCOORD_0 is loaded");
    }
    material.metallic = float(pbr.metallicFactor);
    material.roughness = float(pbr.roughnessFactor);
    if (source.alphaMode == "OPAQUE") material.alphaMode = AlphaMode::Opaque;
    else if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
    else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
    else ctx.fail(object + ": alphaMode must be OPAQUE, MASK or BLEND, got \"" + source.alphaMode + "\"");
    material.alphaCutoff = float(source.alphaCutoff);
    material.doubleSided = source.doubleSided;
    material.unlit = source.extensions.count("KHR_materials_unlit") > 0;
    readShadowExtras(ctx, source.extras, object, material);
    try {
        validateMaterial(material, ctx.scene.textures.size(), object);  // glTF's ranges: factors in [0, 1], cutoff >= 0
    } catch (const Error& e) {
        ctx.fail(e.what());
    }
    return material;
}

}  // namespace

void convertTextures(const LoadContext& ctx) {
    ctx.scene.textures.reserve(ctx.model.textures.size());
    for (size_t i = 0; i < ctx.model.textures.size(); ++i) ctx.scene.textures.push_back(convertTexture(ctx, i));
}

void convertMaterials(const LoadContext& ctx) {
    ctx.scene.materials.reserve(ctx.model.materials.size() + 1);
    for (size_t i = 0; i < ctx.model.materials.size(); ++i) ctx.scene.materials.push_back(convertMaterial(ctx, i));
}

}  // namespace penumbra::gltf
