#pragma once
// Which directional lights get shadow maps this frame (Catlike Coding "Directional Shadows", Lights with
// Shadows).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "shadow_structs.h"
#include "shadows/cascades.h"

namespace penumbra {

struct ReservedDirectionalLight {
    uint32_t sceneLightIndex = 0;  // index into Scene::lights
    float strength = 1.0f;         // Light::shadowStrength
    uint32_t firstTile = 0;        // slot x cascade count: the light's cascades are consecutive tiles
    float normalBias = 1.0f;       // Light::shadowNormalBias, in units of the cascade's filter texel
    float slopeScaleBias = 0.0f;   // Light::shadowBias: slope-scale bias, applied by the lit pass
    bool soft = true;              // LightShadows::Soft: directional.filter; Hard: one bilinear 2x2 PCF tap
    float pcssTanRadius = 0.0f;    // LightShadows::Pcss: tan(shadowLightSize / 2), the sun's angular radius
    float nearPlaneOffset = 0.0f;  // Light::shadowNearPlane: pulls the near plane toward the light
    glm::vec3 wsDirection{0.0f, 0.0f, -1.0f};  // unit direction the light travels
};

// Reserves up to 4 directional lights in scene light order. A light is skipped when its shadows are
// None, its strength <= 0, or no caster (see shadowCasterInstances) meets any cascade sphere extruded
// toward the light: Unity's GetShadowCasterBounds test. No reserved light is not an error.
std::vector<ReservedDirectionalLight> reserveDirectionalShadows(const Scene& scene,
                                                                const std::vector<CascadeSphere>& spheres,
                                                                const std::vector<uint32_t>& casters,
                                                                uint32_t cascadeCount);
// The same into `reserved` (replaced; its storage reused).
void reserveDirectionalShadows(const Scene& scene, const std::vector<CascadeSphere>& spheres,
                               const std::vector<uint32_t>& casters, uint32_t cascadeCount,
                               std::vector<ReservedDirectionalLight>& reserved);

}  // namespace penumbra
