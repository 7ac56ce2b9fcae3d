#pragma once
// Scenes and helpers of the spot/point shadow render tests: small images, compared with the
// ray-traced reference (src/reference) where geometry decides what is shadowed.
#include <nlohmann/json.hpp>

#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"
#include "render_test_support.h"
#include "penumbra/scene_builder.h"
#include "../unit/spot_test_scenes.h"

namespace penumbra::test {

// A 12 m ground, a box and a low wall, one light (spot or point), camera above and in front.
inline Scene boxUnderLight(const Light& light) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    white.roughness = 1.0f;
    const uint32_t material = builder.addMaterial(white);
    builder.addInstance(builder.addMesh(makePlaneMesh({12.0f, 12.0f}, material)), glm::mat4(1.0f), true, "ground");
    glm::mat4 box(1.0f);
    box[3] = glm::vec4(0.3f, 0.5f, -0.2f, 1.0f);
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), material)), box, true, "box");
    glm::mat4 wall(1.0f);
    wall[3] = glm::vec4(-1.6f, 0.75f, 0.8f, 1.0f);
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.15f, 0.75f, 1.0f), material)), wall, true, "wall");
    builder.addLight(light);
    builder.setCamera(makeLookAtCamera({0.0f, 7.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
    return builder.build();
}

inline Light testSpot(LightShadows shadows) {
    Light spot = makeSpotLight({1.2f, 4.0f, 0.6f}, glm::vec3(-0.3f, -1.0f, -0.2f), 60.0f, 12.0f, 0.75f, 0.6f);
    spot.shadows = shadows;
    spot.name = "spot";
    return spot;
}

inline Light testPoint(LightShadows shadows) {
    Light point = makePointLight({0.9f, 2.2f, 0.9f}, 30.0f, 12.0f);
    point.shadows = shadows;
    point.name = "point";
    return point;
}

inline RenderRequest shadowAov(uint32_t light, uint32_t size = 128) {
    RenderRequest request;
    request.width = request.height = size;
    request.output = OutputMode::ShadowAov;
    request.aovLight = light;
    return request;
}

inline Settings smallSpotAtlas(uint32_t size = 1024) {
    Settings settings;
    settings.shadows.spot.atlasSize = size;
    return settings;
}

}  // namespace penumbra::test
