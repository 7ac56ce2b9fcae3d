#pragma once
// The surfaces a frame shows, from its depth buffer: the depth reduction of sample distribution shadow
// maps (SDSM, Lauritzen et al. 2011) that the tight cascade fit needs (fit = tight): the view-depth
// range of the visible surfaces, and their bounds in a light's space per cascade slice.
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/image.h"
#include "penumbra/camera.h"
#include "penumbra/scene.h"

namespace penumbra {

struct VisibleSurfaces {
    std::vector<glm::vec3> wsPoints;  // one per covered pixel
    std::vector<float> vsDepths;      // their view depths
    float vsMinDepth = std::numeric_limits<float>::infinity();
    float vsMaxDepth = 0.0f;
    bool empty() const { return wsPoints.empty(); }
};

// depth: the main view's reversed-Z depth as a D32 target reads back (4 bytes of float
// per pixel, 0 = nothing drawn), view.width x view.height; or, with stride > 1, every stride-th pixel
// of it in x and y (ceil(width / stride) x ceil(height / stride), pixel (x, y) = view pixel
// (x * stride, y * stride)), as the real-time path reads it back.
VisibleSurfaces visibleSurfacesFromDepth(const Image& depth, const CameraView& view, uint32_t stride = 1);
// The same from such depths as raw bytes (width x height floats, rows top to bottom) into `visible`
// (replaced; its storage reused: no allocation once it has held as many points).
void visibleSurfacesFromDepths(const uint8_t* depths, uint32_t width, uint32_t height, const CameraView& view,
                               uint32_t stride, VisibleSurfaces& visible);

// The depth of pixel (x, y) of such an image (4 bytes of float per pixel).
float depthAt(const Image& depth, uint32_t x, uint32_t y);
// The world position seen at pixel position (px, py) of the view (pixel centres at half-integers) at
// reversed-Z depth `depth`; worldFromClip = inverse(view.clipFromWorld), computed once by the caller.
glm::vec3 wsPositionFromDepth(const glm::mat4& worldFromClip, const CameraView& view, float px, float py, float depth);

// Calls visit(wsPosition, vsDepth) for every pixel of such an image (view.width x view.height) with
// geometry (reversed-Z depth > 0), at the pixel's centre, rows top to bottom: the virtual shadow maps'
// page marking references walk the view's depth this way.
template <typename Visit>
void forEachSurfacePixel(const Image& depth, const CameraView& view, Visit&& visit) {
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld);
    for (uint32_t y = 0; y < depth.height; ++y)
        for (uint32_t x = 0; x < depth.width; ++x) {
            const float d = depthAt(depth, x, y);
            if (!(d > 0.0f)) continue;  // reversed Z: 0 = nothing drawn
            const glm::vec3 wsPosition = wsPositionFromDepth(worldFromClip, view, float(x) + 0.5f, float(y) + 0.5f, d);
            visit(wsPosition, -(view.viewFromWorld * glm::vec4(wsPosition, 1.0f)).z);
        }
}

// Bounds in the light's rotation-only space (lightRotationFromWorld) of the visible points whose view
// depth lies in [vsNear, vsFar]; invalid when there are none.
Aabb rotatedVisibleBounds(const VisibleSurfaces& visible, const glm::mat4& lightRotation, float vsNear, float vsFar);

}  // namespace penumbra
