#include "shadows/visible_surfaces.h"

#include <cstring>

#include "core/error.h"

namespace penumbra {

VisibleSurfaces visibleSurfacesFromDepth(const Image& depth, const CameraView& view, uint32_t stride) {
    PENUMBRA_ASSERT(stride >= 1 && depth.width == (view.width + stride - 1) / stride &&
                    depth.height == (view.height + stride - 1) / stride && depth.channels == 4);
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld);
    VisibleSurfaces visible;
    visible.wsPoints.reserve(size_t(depth.width) * depth.height);
    visible.vsDepths.reserve(size_t(depth.width) * depth.height);
    for (uint32_t y = 0; y < depth.height; ++y) {
        for (uint32_t x = 0; x < depth.width; ++x) {
            float d = 0.0f;
            std::memcpy(&d, &depth.pixels[(size_t(y) * depth.width + x) * 4], sizeof(float));
            if (!(d > 0.0f)) continue;  // reversed Z: 0 = the far plane, nothing drawn
            // Pixel centres, Vulkan NDC (y down): the camera convention of camera_view.h.
            const float px = float(x * stride) + 0.5f, py = float(y * stride) + 0.5f;
            const glm::vec4 clip(2.0f * px / float(view.width) - 1.0f, 2.0f * py / float(view.height) - 1.0f, d, 1.0f);
            const glm::vec4 h = worldFromClip * clip;
            const glm::vec3 wsPoint = glm::vec3(h) / h.w;
            const float vsDepth = -(view.viewFromWorld * glm::vec4(wsPoint, 1.0f)).z;
            visible.wsPoints.push_back(wsPoint);
            visible.vsDepths.push_back(vsDepth);
            visible.vsMinDepth = std::min(visible.vsMinDepth, vsDepth);
            visible.vsMaxDepth = std::max(visible.vsMaxDepth, vsDepth);
        }
    }
    return visible;
}

Aabb rotatedVisibleBounds(const VisibleSurfaces& visible, const glm::mat4& lightRotation, float vsNear, float vsFar) {
    const glm::mat3 rotation(lightRotation);
    Aabb bounds;
    for (size_t i = 0; i < visible.wsPoints.size(); ++i) {
        if (visible.vsDepths[i] < vsNear || visible.vsDepths[i] > vsFar) continue;
        bounds.extend(rotation * visible.wsPoints[i]);
    }
    return bounds;
}

}  // namespace penumbra
