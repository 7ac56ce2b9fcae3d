#include "penumbra/scene.h"

namespace penumbra {

Aabb Aabb::transformed(const glm::mat4& m) const {
    Aabb result;
    if (!valid()) return result;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
        result.extend(glm::vec3(m * glm::vec4(corner, 1.0f)));
    }
    return result;
}

}  // namespace penumbra
