#pragma once
// The surfaces a frame shows, from its depth buffer: the depth reduction of sample distribution shadow
// maps (SDSM, Lauritzen et al. 2011) that the tight cascade fit needs (fit = tight): the view-depth
// range of the visible surfaces, and their bounds in a light's space per cascade slice.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/image.h"
#include "penumbra/camera.h"
#include "penumbra/scene.h"

namespace penumbra {

// The visible surfaces binned by view depth (log-spaced bins; the first takes everything nearer, the
// last everything farther), each bin's bounds kept in a few rotated spaces: what the GPU's reduction
// reads back (render/visible_surface_pass.h, shaders/shared/visible_bounds_structs.h), 120 KiB whatever
// the view's size.
struct VisibleDepthBins {
    static constexpr uint32_t kBins = 1024;    // = gpu_data::kVisibleDepthBins
    static constexpr uint32_t kMaxSpaces = 5;  // = gpu_data::kVisibleBoundsSpaces
    float vsBinNear = 0.0f;                    // bin b starts at vsBinNear * exp(b / binsPerLogDepth)
    float binsPerLogDepth = 0.0f;
    uint32_t spaceCount = 0;
    std::array<glm::mat3, kMaxSpaces> spaceFromWorld{};  // rotations
    std::vector<Aabb> rsBounds;                          // [space * kBins + bin]; invalid: no surface there
};

// The surfaces a view shows: every point (a one-shot frame's exact reduction), or only their bins (a
// real-time frame's, from the GPU).
struct VisibleSurfaces {
    std::vector<glm::vec3> wsPoints;  // one per covered pixel (empty when binned)
    std::vector<float> vsDepths;      // their view depths
    VisibleDepthBins bins;            // used when wsPoints is empty
    float vsMinDepth = std::numeric_limits<float>::infinity();
    float vsMaxDepth = 0.0f;
    bool empty() const { return !(vsMinDepth <= vsMaxDepth); }
};

// depth: the main view's reversed-Z depth as a D32 target reads back (4 bytes of float per pixel,
// 0 = nothing drawn), view.width x view.height: every covered pixel's point (forEachSurfacePixel).
VisibleSurfaces visibleSurfacesFromDepth(const Image& depth, const CameraView& view);

// The depth of pixel (x, y) of such an image (4 bytes of float per pixel).
float depthAt(const Image& depth, uint32_t x, uint32_t y);
// The world position seen at pixel position (px, py) of the view (pixel centres at half-integers) at
// reversed-Z depth `depth`; worldFromClip = inverse(view.clipFromWorld), computed once by the caller.
glm::vec3 wsPositionFromDepth(const glm::mat4& worldFromClip, const CameraView& view, float px, float py, float depth);

// Calls visit(wsPosition, vsDepth) for every pixel of such an image (view.width x view.height) with
// geometry (reversed-Z depth > 0), at the pixel's centre, rows top to bottom: visibleSurfacesFromDepth
// and the virtual shadow maps' page marking references walk the view's depth this way.
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
// depth lies in [vsNear, vsFar]; invalid when there are none. Binned surfaces give bounds that hold
// those points and may hold the points of the neighbouring bins too (a bin and one more on either
// side of the range, for the rounding of the bin of a depth); a rotation that is none of their spaces
// gets the bounds of the closest space's box, rotated: larger, still holding every point.
Aabb rotatedVisibleBounds(const VisibleSurfaces& visible, const glm::mat4& lightRotation, float vsNear, float vsFar);

// The words of the GPU's reduction (visible_bounds_structs.h layout, kVisibleBoundsWords of them) into
// `visible` (replaced; its storage reused), with the bins and spaces it was recorded with.
void visibleSurfacesFromBoundsWords(const uint32_t* words, float vsBinNear, float binsPerLogDepth,
                                    std::span<const glm::mat4> spaceFromWorld, VisibleSurfaces& visible);
// The CPU reference of that reduction: the points' bins and bounds in each space (at most kMaxSpaces),
// the bins log-spaced over [vsBinNear, vsBinFar] (vsBinFar > vsBinNear > 0).
VisibleSurfaces binVisibleSurfaces(const VisibleSurfaces& points, std::span<const glm::mat4> spaceFromWorld,
                                   float vsBinNear, float vsBinFar);
// The bins' spacing for [vsBinNear, vsBinFar]: kBins / log(vsBinFar / vsBinNear).
float visibleBinsPerLogDepth(float vsBinNear, float vsBinFar);

}  // namespace penumbra
