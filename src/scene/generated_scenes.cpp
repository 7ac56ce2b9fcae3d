#include "scene/generated_scenes.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "penumbra/scene_builder.h"
#include "scene/canonical_scene_parts.h"

namespace penumbra {

namespace {

constexpr float kModelSize = 2.0f;     // each field copy is scaled to this largest extent, metres
constexpr float kFieldSpacing = 3.0f;  // grid spacing of the field
constexpr float kBoxSpacing = 1.2f;

uint32_t parseCount(const std::string& text, const std::string& source, const char* what, uint32_t lo, uint32_t hi) {
    const bool digits = !text.empty() && text.size() <= 9 && std::all_of(text.begin(), text.end(), ::isdigit);
    const unsigned long value = digits ? std::stoul(text) : 0;
    if (!digits || value < lo || value > hi)
        throw Error("scene " + source + ": " + what + " '" + text + "' must be an integer in " + std::to_string(lo) +
                    ".." + std::to_string(hi));
    return uint32_t(value);
}

// The nearest camera along `wsDirection` from the origin whose view (at aspect 1, so every wider
// output sees it too) holds every corner of `wsBounds` with a small margin.
Camera framingCamera(const Aabb& wsBounds, const glm::vec3& wsDirection, float yfov) {
    for (float distance = 1.0f;; distance *= 1.05f) {
        Camera camera = makeLookAtCamera(distance * glm::normalize(wsDirection), glm::vec3(0.0f), yfov, 0.1f);
        const glm::mat4 viewFromWorld = glm::inverse(camera.worldFromView);
        const float limit = 0.95f * std::tan(0.5f * yfov);
        bool inside = true;
        for (int corner = 0; corner < 8 && inside; ++corner) {
            const glm::vec3 p((corner & 1) ? wsBounds.max.x : wsBounds.min.x, (corner & 2) ? wsBounds.max.y : wsBounds.min.y,
                              (corner & 4) ? wsBounds.max.z : wsBounds.min.z);
            const glm::vec3 v = glm::vec3(viewFromWorld * glm::vec4(p, 1.0f));
            inside = -v.z > 0.1f && std::abs(v.x) <= limit * -v.z && std::abs(v.y) <= limit * -v.z;
        }
        if (inside) return camera;
    }
}

// A ground of `halfSize` around the origin, a sun from the upper left, a camera looking down on the
// square [-halfSize, halfSize]^2 (and `height` above it) from its front-left corner.
void addGroundSunCamera(SceneBuilder& builder, float halfSize, float height) {
    const uint32_t ground = builder.addMaterial(canonical::colored("ground", glm::vec3(0.55f, 0.55f, 0.5f)));
    const float side = 2.0f * halfSize + 4.0f;
    builder.addInstance(builder.addMesh(makePlaneMesh(glm::vec2(side), ground)), glm::mat4(1.0f), true, "ground");
    Light sun = makeDirectionalLight(glm::vec3(-0.45f, -1.0f, -0.35f), 3.0f);
    sun.name = "sun";
    builder.addLight(sun);
    Aabb field;
    field.extend(glm::vec3(-halfSize, 0.0f, -halfSize));
    field.extend(glm::vec3(halfSize, height, halfSize));
    Camera camera = framingCamera(field, glm::vec3(-1.0f, 0.9f, 1.0f), 0.9f);
    camera.name = "camera";
    builder.setCamera(camera);
}

// `count` unshadowed point lights on a jittered grid over [-halfSize, halfSize]^2, 0.5-1.5 m up, each
// reaching about 2.5 grid spacings (1.5-8 m), in four colours.
void addPointLights(SceneBuilder& builder, float halfSize, uint32_t count) {
    if (count == 0) return;
    const uint32_t side = uint32_t(std::ceil(std::sqrt(double(count))));
    const float spacing = 2.0f * halfSize / float(side);
    const float range = std::clamp(2.5f * spacing, 1.5f, 8.0f);
    const glm::vec3 colors[4] = {{1.0f, 0.6f, 0.4f}, {0.5f, 0.7f, 1.0f}, {0.6f, 1.0f, 0.6f}, {1.0f, 0.5f, 0.9f}};
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t hash = (i * 2246822519u) ^ (i >> 5);
        const glm::vec3 jitter(float(hash % 101) / 100.0f - 0.5f, 0.5f + float((hash >> 8) % 101) / 100.0f,
                               float((hash >> 16) % 101) / 100.0f - 0.5f);
        const glm::vec3 wsPosition(spacing * (float(i % side) + 0.5f + 0.5f * jitter.x) - halfSize, jitter.y,
                                   spacing * (float(i / side) + 0.5f + 0.5f * jitter.z) - halfSize);
        Light point = makePointLight(wsPosition, 2.0f, range);
        point.name = "point" + std::to_string(i);
        point.color = colors[i % 4];
        point.shadows = LightShadows::None;
        builder.addLight(point);
    }
}

}  // namespace

std::optional<GeneratedSceneSpec> parseGeneratedSceneSpec(const std::string& source) {
    if (source.rfind("gen:", 0) != 0) return std::nullopt;
    std::vector<std::string> parts;
    std::stringstream stream(source.substr(4));
    for (std::string part; std::getline(stream, part, ':');) parts.push_back(part);
    GeneratedSceneSpec spec;
    if (!parts.empty() && parts[0] == "field" && parts.size() >= 2 && parts.size() <= 4) {
        spec.kind = GeneratedSceneSpec::Kind::Field;
        spec.count = parseCount(parts[1], source, "the copy count", 1, kMaxFieldCopies);
        if (parts.size() >= 3) spec.spotLights = parseCount(parts[2], source, "the spot light count", 0, kMaxFieldSpotLights);
        if (parts.size() == 4) spec.pointLights = parseCount(parts[3], source, "the point light count", 0, kMaxPointLights);
        return spec;
    }
    if (!parts.empty() && parts[0] == "boxes" && (parts.size() == 2 || parts.size() == 3)) {
        spec.kind = GeneratedSceneSpec::Kind::Boxes;
        spec.count = parseCount(parts[1], source, "the box count", 1, kMaxBoxes);
        if (parts.size() == 3) spec.pointLights = parseCount(parts[2], source, "the point light count", 0, kMaxPointLights);
        return spec;
    }
    throw Error("scene " + source + ": unknown built-in scene (use gen:field:N[:S[:P]] or gen:boxes:N[:P])");
}

Scene makeFieldScene(const Scene& model, uint32_t copies, uint32_t spotLights, uint32_t pointLights) {
    if (!model.wsBounds.valid()) throw Error("gen:field: the model has no geometry");
    SceneBuilder builder;
    for (const Texture& texture : model.textures) builder.addTexture(texture);
    for (const Material& material : model.materials) builder.addMaterial(material);
    for (const Mesh& mesh : model.meshes) builder.addMesh(mesh);
    // Normalize: largest extent kModelSize, centred over the origin, standing on y = 0.
    const glm::vec3 extent = model.wsBounds.extent();
    const float scale = kModelSize / std::max({extent.x, extent.y, extent.z, 1e-6f});
    const glm::vec3 base(model.wsBounds.center().x, model.wsBounds.min.y, model.wsBounds.center().z);
    const glm::mat4 normalize = glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -base);
    const uint32_t side = uint32_t(std::ceil(std::sqrt(double(copies))));
    const float halfSize = 0.5f * kFieldSpacing * float(side);
    for (uint32_t copy = 0; copy < copies; ++copy) {
        const glm::vec3 wsCenter(kFieldSpacing * (float(copy % side) + 0.5f) - halfSize, 0.0f,
                                 kFieldSpacing * (float(copy / side) + 0.5f) - halfSize);
        const glm::mat4 place = glm::rotate(glm::translate(glm::mat4(1.0f), wsCenter), glm::radians(37.0f * float(copy)),
                                            glm::vec3(0, 1, 0)) * normalize;
        for (const Instance& instance : model.instances)
            builder.addInstance(instance.meshIndex, place * instance.worldFromObject, instance.castShadows,
                                "copy" + std::to_string(copy) + "/" + instance.nodeName);
    }
    addGroundSunCamera(builder, halfSize, kModelSize);
    // Spot lights on a grid over the field, 6 m up, each aimed at the ground a little off vertical.
    const uint32_t spotSide = uint32_t(std::ceil(std::sqrt(double(std::max(spotLights, 1u)))));
    const float spotSpacing = 2.0f * halfSize / float(spotSide);
    const glm::vec3 colors[4] = {{1.0f, 0.85f, 0.7f}, {0.7f, 0.85f, 1.0f}, {0.85f, 1.0f, 0.75f}, {1.0f, 0.75f, 0.9f}};
    for (uint32_t i = 0; i < spotLights; ++i) {
        const glm::vec3 wsPosition(spotSpacing * (float(i % spotSide) + 0.5f) - halfSize, 6.0f,
                                   spotSpacing * (float(i / spotSide) + 0.5f) - halfSize);
        Light spot = makeSpotLight(wsPosition, glm::vec3(0.15f, -1.0f, 0.1f), 40.0f, 18.0f, glm::radians(40.0f),
                                   glm::radians(30.0f));
        spot.name = "spot" + std::to_string(i);
        spot.color = colors[i % 4];
        builder.addLight(spot);
    }
    addPointLights(builder, halfSize, pointLights);
    return builder.build();
}

Scene makeBoxesScene(uint32_t boxes, uint32_t pointLights) {
    SceneBuilder builder;
    const glm::vec3 colors[4] = {{0.8f, 0.3f, 0.25f}, {0.3f, 0.6f, 0.8f}, {0.85f, 0.75f, 0.3f}, {0.45f, 0.75f, 0.4f}};
    uint32_t meshes[4];
    for (uint32_t i = 0; i < 4; ++i)
        meshes[i] = builder.addMesh(makeBoxMesh(glm::vec3(0.3f, 0.5f, 0.3f), builder.addMaterial(canonical::colored("box", colors[i]))));
    const uint32_t side = uint32_t(std::ceil(std::sqrt(double(boxes))));
    const float halfSize = 0.5f * kBoxSpacing * float(side);
    for (uint32_t i = 0; i < boxes; ++i) {
        // A fixed integer hash gives each box its height and turn, the same on every run.
        const uint32_t hash = (i * 2654435761u) ^ (i >> 7);
        const float height = 0.4f + 1.2f * float(hash % 1000) / 1000.0f;
        const glm::vec3 wsCenter(kBoxSpacing * (float(i % side) + 0.5f) - halfSize, 0.5f * height,
                                 kBoxSpacing * (float(i / side) + 0.5f) - halfSize);
        glm::mat4 worldFromObject = glm::translate(glm::mat4(1.0f), wsCenter);
        worldFromObject = glm::rotate(worldFromObject, float(hash % 628) * 0.01f, glm::vec3(0, 1, 0));
        worldFromObject = glm::scale(worldFromObject, glm::vec3(1.0f, height, 1.0f));
        builder.addInstance(meshes[i % 4], worldFromObject, true, "");
    }
    addGroundSunCamera(builder, halfSize, 1.6f);
    addPointLights(builder, halfSize, pointLights);
    return builder.build();
}

}  // namespace penumbra
