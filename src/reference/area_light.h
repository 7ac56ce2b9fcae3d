#pragma once
// The ray-traced reference's area lights (penumbra reference --soft, for shadows "pcss"): the light as a
// disk, the sun's of angular diameter shadowLightSize degrees, a spot or point light's of radius
// shadowLightSize metres facing the shaded point; the shadow term is the fraction of shadow rays to
// points of that disk that reach it.
#include <cstdint>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// Sample i of n on the unit disk (Vogel's golden-angle spiral, area-uniform), turned by `rotation`.
glm::vec2 vogelDiskSample(uint32_t i, uint32_t n, float rotation);

struct AreaLightRay {
    glm::vec3 wsDirection{0.0f};  // unit, toward the light's disk point
    float tFar = 0.0f;            // ray length: infinite for the sun
};

// The shadow ray from wsOrigin to the point `disk` (on the unit disk) of the light's disk. epsilon
// shortens rays to spot and point lights so they stop short of the emitter.
AreaLightRay areaLightRay(const Light& light, const glm::vec3& wsOrigin, glm::vec2 disk, float epsilon);

}  // namespace penumbra
