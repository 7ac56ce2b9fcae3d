#include "shadows/spot_projection.h"

#include <cmath>

#include "core/error.h"
#include "shadows/cascades.h"

namespace penumbra {

glm::mat4 perspectiveLightFromWorld(const glm::vec3& wsPosition, const glm::vec3& wsDirection) {
    glm::mat4 m = lightRotationFromWorld(wsDirection);
    m[3] = glm::vec4(-glm::vec3(m * glm::vec4(wsPosition, 0.0f)), 1.0f);
    return m;
}

glm::mat4 perspectiveClipFromLight(float tanHalfFov, float nearDistance, float farDistance) {
    PENUMBRA_ASSERT(tanHalfFov > 0.0f && nearDistance > 0.0f && farDistance > nearDistance);
    const float depthScale = farDistance / (farDistance - nearDistance);
    glm::mat4 m(0.0f);  // m[column][row]
    m[0][0] = 1.0f / tanHalfFov;
    m[1][1] = -1.0f / tanHalfFov;  // Vulkan NDC y points down; light-space +Y is the tile's top
    m[2][2] = -depthScale;         // z_clip = depthScale * (d - near) with d = -z
    m[3][2] = -depthScale * nearDistance;
    m[2][3] = -1.0f;               // w = d
    return m;
}

float tanHalfFovWithMargin(float coneTangent, uint32_t tileSize, float marginTexels) {
    const float usable = std::max(float(tileSize) - 2.0f * marginTexels, 1.0f);
    return coneTangent * float(tileSize) / usable;
}

const std::array<glm::vec3, 6>& pointLightFaceDirections() {
    static const std::array<glm::vec3, 6> faces = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                                   glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
    return faces;
}

uint32_t pointLightFaceOf(const glm::vec3& wsFromLight) {
    const glm::vec3 a = glm::abs(wsFromLight);
    // Ties go to the lower axis, as in the GLSL twin (penumbra/shadows.glsl otherShadowTile).
    const uint32_t axis = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (wsFromLight[int(axis)] < 0.0f ? 1u : 0u);
}

}  // namespace penumbra
