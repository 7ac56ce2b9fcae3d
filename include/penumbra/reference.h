#pragma once
// Ray-traced ground truth for the `--aov shadow` image (docs/cli.md: the images and their conventions):
// one camera ray per pixel centre with the rasterizer's camera convention, one shadow ray from the
// visible surface to the light, and a mask of the pixels where a comparison is meaningful.
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include <penumbra/image.h>
#include <penumbra/camera.h>
#include <penumbra/scene.h>
#include <penumbra/settings.h>

namespace penumbra {

struct ReferenceImages {
    // 1 channel: round(255 × (1 - strength × fade × (1 - visibility))), visibility 0 or 1 (or the
    // fraction of visible rays with softSamples);
    // 255 where no geometry is visible or the surface doesn't receive shadows.
    Image shadow;
    // 1 channel: 255 = the pixel takes part in comparisons, 0 = excluded (see traceReferenceShadow).
    Image validMask;
    uint64_t validPixels = 0;
    uint64_t geometryPixels = 0;  // pixels whose camera ray hits a visible surface
    // Per pixel (row-major, pixel (0,0) top-left): the view depth of the surface the camera ray hits
    // (as traceViewDepth gives it), +infinity where it hits none.
    std::vector<float> viewDepth;
};

// The shadow settings that shape the AOV beyond the light itself (maximum distance and fade). Defaults
// mean "no maximum distance": no fade, every distance is compared.
struct ReferenceOptions {
    float maxShadowDistance = std::numeric_limits<float>::infinity();  // view depth where shadows end
    float distanceFade = 0.1f;  // fraction of maxShadowDistance over which shadows fade out
    // false: linear in view depth; true: linear in the squared camera distance (Unity URP's fade; the
    // setting shadows.fadeMode = squared), over the same band.
    bool squaredFade = false;
    // 0: one shadow ray to the light's centre (a point light). N > 0: the light is a disk of
    // shadowLightSize (src/reference/area_light.h) and each pixel's shadow term is the fraction of N rays to it that
    // reach it: the truth for pcss shadows (penumbra reference --soft N).
    uint32_t softSamples = 0;
    // For a caller on another thread (the viewer's reference view): the rows traced so far are added
    // to *rowsDone (view.height in all), and once *cancel is true the remaining rows are
    // skipped (the result is then incomplete: discard it). Either may be null.
    std::atomic<uint32_t>* rowsDone = nullptr;
    const std::atomic<bool>* cancel = nullptr;
};

// The options that match the rasterizer's shadow term for `settings` and `view`: its shadow distance
// (maxDistance, or the camera's far plane when nearer) and its distance fade.
ReferenceOptions referenceOptionsFor(const Settings& settings, const CameraView& view, uint32_t softSamples);

// Traces light `lightIndex`'s shadow as seen by `view`. A pixel is valid when all of these hold:
// - its camera ray hits a visible surface;
// - N·L >= 0.1 for both the shading and the geometric normal, turned to face the camera (the
//   grazing terminator is where shadow maps legitimately disagree with rays);
// - the point is inside a spot light's outer cone and within a spot or point light's range;
// - it is not in the distance-fade band nor beyond maxShadowDistance;
// - none of its 8 neighbours is across a discontinuity: no geometry, another instance, a geometric
//   normal more than ~25° away (cos < 0.9, creases), or a point farther than 2 pixel footprints from
//   this pixel's tangent plane (depth steps). Such pixels straddle edges that rasterization and ray
//   casting may assign to different surfaces.
// A scene with nothing in view gives all-255 shadow and validPixels == 0.
// Throws penumbra::Error when the light doesn't exist or casts no shadows (shadows none or strength 0).
// Runs on all cores (TBB); shows progress on stderr when `showProgress` and stderr is a terminal.
ReferenceImages traceReferenceShadow(const Scene& scene, const CameraView& view, uint32_t lightIndex,
                                     bool showProgress, const ReferenceOptions& options = {});

// The view depth (distance along the camera's forward axis, in scene units) of the surface that the
// camera ray through each pixel centre hits, with the camera rays of traceReferenceShadow (the surfaces
// the rasterizer's opaque pass draws, between the near and far planes); +infinity where no surface is
// hit. Row-major, view.width x view.height, pixel (0,0) top-left. Runs on all cores (TBB).
std::vector<float> traceViewDepth(const Scene& scene, const CameraView& view);

}  // namespace penumbra
