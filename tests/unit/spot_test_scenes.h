#pragma once
// Small scenes for the spot/point light shadow tests (unit and render): a ground plane with spot
// lights in a grid, each above its own box, seen from straight above.
#include <cmath>

#include "penumbra/scene_builder.h"

namespace penumbra::test {

// count spot lights on a 4-wide grid (spacing 4 m) at height 4, pointing down, 30° cone, range 10,
// each with a 0.8 m box 1 m above the ground under it. Camera 24 m above the grid's centre.
// lightOffset moves each light sideways (it still aims at the ground under its box), so that the box's
// shadow falls beside the box where the camera above sees it.
inline Scene spotGridScene(uint32_t count, LightShadows shadows = LightShadows::Soft,
                           glm::vec3 lightOffset = glm::vec3(0.0f)) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    white.roughness = 1.0f;
    const uint32_t material = builder.addMaterial(white);
    const uint32_t ground = builder.addMesh(makePlaneMesh({40.0f, 40.0f}, material));
    const uint32_t box = builder.addMesh(makeBoxMesh(glm::vec3(0.4f), material));
    builder.addInstance(ground, glm::mat4(1.0f), true, "ground");
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 base(-6.0f + 4.0f * float(i % 4), 0.0f, -6.0f + 4.0f * float(i / 4));
        glm::mat4 transform(1.0f);
        transform[3] = glm::vec4(base + glm::vec3(0.0f, 1.0f, 0.0f), 1.0f);
        builder.addInstance(box, transform, true, "box" + std::to_string(i));
        const glm::vec3 wsLight = base + glm::vec3(0.0f, 4.0f, 0.0f) + lightOffset;
        Light light = makeSpotLight(wsLight, base - wsLight, 50.0f, 10.0f, 0.5235988f, 0.4f);
        light.shadows = shadows;
        light.name = "spot" + std::to_string(i);
        builder.addLight(light);
    }
    builder.setCamera(makeLookAtCamera({0.0f, 24.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.8f));
    return builder.build();
}

}  // namespace penumbra::test
