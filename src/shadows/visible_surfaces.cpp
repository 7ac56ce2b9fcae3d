#include "shadows/visible_surfaces.h"

#include <cstring>
#include <limits>

#include "core/error.h"

namespace penumbra {

void visibleSurfacesFromDepths(const uint8_t* depths, uint32_t width, uint32_t height, const CameraView& view,
                               uint32_t stride, VisibleSurfaces& visible) {
    PENUMBRA_ASSERT(stride >= 1 && width == (view.width + stride - 1) / stride &&
                    height == (view.height + stride - 1) / stride);
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld);
    visible.wsPoints.clear();
    visible.vsDepths.clear();
    visible.vsMinDepth = std::numeric_limits<float>::infinity();
    visible.vsMaxDepth = 0.0f;
    visible.wsPoints.reserve(size_t(width) * height);
    visible.vsDepths.reserve(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            float d = 0.0f;
            std::memcpy(&d, depths + (size_t(y) * width + x) * 4, sizeof(float));
            if (!(d > 0.0f)) continue;  // reversed Z: 0 = the far plane, nothing drawn
            const glm::vec3 wsPoint =
                wsPositionFromDepth(worldFromClip, view, float(x * stride) + 0.5f, float(y * stride) + 0.5f, d);
            const float vsDepth = -(view.viewFromWorld * glm::vec4(wsPoint, 1.0f)).z;
            visible.wsPoints.push_back(wsPoint);
            visible.vsDepths.push_back(vsDepth);
            visible.vsMinDepth = std::min(visible.vsMinDepth, vsDepth);
            visible.vsMaxDepth = std::max(visible.vsMaxDepth, vsDepth);
        }
    }
}

VisibleSurfaces visibleSurfacesFromDepth(const Image& depth, const CameraView& view, uint32_t stride) {
    PENUMBRA_ASSERT(depth.channels == 4);
    VisibleSurfaces visible;
    visibleSurfacesFromDepths(depth.pixels.data(), depth.width, depth.height, view, stride, visible);
    return visible;
}

float depthAt(const Image& depth, uint32_t x, uint32_t y) {
    float d = 0.0f;
    std::memcpy(&d, &depth.pixels[(size_t(y) * depth.width + x) * 4], sizeof(float));
    return d;
}

glm::vec3 wsPositionFromDepth(const glm::mat4& worldFromClip, const CameraView& view, float px, float py, float depth) {
    // Vulkan NDC (y down): the camera convention of camera_view.h.
    const glm::vec4 clip(2.0f * px / float(view.width) - 1.0f, 2.0f * py / float(view.height) - 1.0f, depth, 1.0f);
    const glm::vec4 h = worldFromClip * clip;
    return glm::vec3(h) / h.w;
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
