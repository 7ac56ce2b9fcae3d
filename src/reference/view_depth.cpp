// traceViewDepth: the depth of the surface each pixel sees, with the reference's camera rays.
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/reference.h"
#include "reference/embree_scene.h"

namespace penumbra {

std::vector<float> traceViewDepth(const Scene& scene, const CameraView& view) {
    const EmbreeScene tracer(scene);
    const uint32_t width = view.width, height = view.height;
    constexpr float kNoSurface = std::numeric_limits<float>::infinity();
    std::vector<float> viewDepth(size_t(width) * height, kNoSurface);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height), [&](const tbb::blocked_range<uint32_t>& rows) {
        for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const glm::vec3 wsDirection = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
                // Near and far are planes perpendicular to the view axis, as in the rasterizer.
                const float cosForward = glm::dot(wsDirection, view.wsForward);
                if (cosForward <= 0.0f) continue;
                const float tNear = view.zNear / cosForward;
                const float tFar = std::isinf(view.zFar) ? kNoSurface : view.zFar / cosForward;
                const std::optional<SurfaceHit> hit = tracer.intersectCamera(view.wsPosition, wsDirection, tNear, tFar);
                if (hit) viewDepth[size_t(y) * width + x] = hit->t * cosForward;
            }
        }
    });
    return viewDepth;
}

}  // namespace penumbra
