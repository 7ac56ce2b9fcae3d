// KHR_lights_punctual lights with their shadow extras. Scene::lights[i] is the extension's lights[i].
#include <cmath>

#include "scene/gltf_internal.h"

namespace penumbra::gltf {
namespace {

constexpr float kHalfPi = 1.5707963268f;

void readShadowExtras(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object, Light& light) {
    if (auto mode = extraEnum(ctx, extras, object, "shadows", {"none", "hard", "soft", "pcss"}))
        light.shadows = LightShadows(*mode);
    if (auto v = extraNumber(ctx, extras, object, "shadowStrength", 0.0f, 1.0f)) light.shadowStrength = *v;
    const float kInf = INFINITY;
    if (auto v = extraNumber(ctx, extras, object, "shadowBias", 0.0f, kInf)) light.shadowBias = *v;
    if (auto v = extraNumber(ctx, extras, object, "shadowNormalBias", 0.0f, kInf)) light.shadowNormalBias = *v;
    if (auto v = extraNumber(ctx, extras, object, "shadowNearPlane", 0.0f, kInf)) light.shadowNearPlane = *v;
    light.shadowLightSize = defaultShadowLightSize(light.type);
    const float maxSize = light.type == LightType::Directional ? 20.0f : kInf;  // degrees: a sun-like disk
    if (auto v = extraNumber(ctx, extras, object, "shadowLightSize", 0.0f, maxSize)) light.shadowLightSize = *v;
}

Light convertLight(const LoadContext& ctx, size_t index) {
    const tinygltf::Light& source = ctx.model.lights[index];
    const std::string object = describe("light", index, source.name);
    Light light;
    light.name = source.name;
    if (source.type == "directional") light.type = LightType::Directional;
    else if (source.type == "spot") light.type = LightType::Spot;
    else if (source.type == "point") light.type = LightType::Point;
    else ctx.fail(object + ": type must be \"directional\", \"spot\" or \"point\", got \"" + source.type + "\"");
    if (!source.color.empty()) {
        if (source.color.size() != 3) ctx.fail(object + ": color must have 3 components");
        light.color = glm::vec3(float(source.color[0]), float(source.color[1]), float(source.color[2]));
    }
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(light.color[c]) || light.color[c] < 0.0f)
            ctx.fail(object + ": color must be finite and >= 0");
    light.intensity = float(source.intensity);
    if (!std::isfinite(light.intensity) || light.intensity < 0.0f)
        ctx.fail(object + ": intensity must be finite and >= 0");
    light.range = float(source.range);
    if (!std::isfinite(light.range) || light.range < 0.0f) ctx.fail(object + ": range must be finite and > 0");
    if (light.type == LightType::Spot) {
        light.innerConeAngle = float(source.spot.innerConeAngle);
        light.outerConeAngle = float(source.spot.outerConeAngle);
        if (!(light.outerConeAngle > 0.0f && light.outerConeAngle <= kHalfPi))
            ctx.fail(object + ": spot.outerConeAngle must be in (0, pi/2]");
        if (!(light.innerConeAngle >= 0.0f)) ctx.fail(object + ": spot.innerConeAngle must be >= 0");
        if (light.innerConeAngle >= light.outerConeAngle) {
            // The spec wants inner < outer; some exporters write them equal. Keep a thin falloff band.
            ctx.warn(object + ": spot.innerConeAngle is not below outerConeAngle, clamped");
            light.innerConeAngle = 0.99f * light.outerConeAngle;
        }
    }
    // docs/scene-format.md: the near plane defaults to 0 for directional lights, 0.1 for spot and point.
    light.shadowNearPlane = light.type == LightType::Directional ? 0.0f : 0.1f;
    readShadowExtras(ctx, source.extras, object, light);
    return light;
}

}  // namespace

void convertLights(const LoadContext& ctx) {
    ctx.scene.lights.reserve(ctx.model.lights.size());
    for (size_t i = 0; i < ctx.model.lights.size(); ++i) ctx.scene.lights.push_back(convertLight(ctx, i));
}

void placeLight(const LoadContext& ctx, const std::string& object, Light& light, const glm::mat4& worldFromNode) {
    light.wsPosition = glm::vec3(worldFromNode[3]);
    const glm::vec3 wsMinusZ = -glm::vec3(worldFromNode[2]);
    const float len = glm::length(wsMinusZ);
    if (std::isfinite(len) && len > 0.0f) {
        light.wsDirection = wsMinusZ / len;
    } else if (light.type != LightType::Point) {
        ctx.fail(object + ": the light's direction is undefined (the node's -Z axis has zero length: a zero scale)");
    }
}

int nodeLightIndex(const LoadContext& ctx, size_t nodeIndex) {
    const tinygltf::Node& node = ctx.model.nodes[nodeIndex];
    const auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) return -1;
    const tinygltf::Value& ext = it->second;
    const std::string object = describe("node", nodeIndex, node.name);
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
        ctx.fail(object + ": KHR_lights_punctual.light must be an integer light index");
    const int index = ext.Get("light").GetNumberAsInt();
    if (index < 0 || size_t(index) >= ctx.scene.lights.size())
        ctx.fail(object + ": KHR_lights_punctual.light " + std::to_string(index) + " is out of range (the file has " +
                 std::to_string(ctx.scene.lights.size()) + " lights)");
    return index;
}

}  // namespace penumbra::gltf
