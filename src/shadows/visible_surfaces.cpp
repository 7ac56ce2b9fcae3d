#include "shadows/visible_surfaces.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "visible_bounds_structs.h"

namespace penumbra {

static_assert(VisibleDepthBins::kBins == gpu_data::kVisibleDepthBins);
static_assert(VisibleDepthBins::kMaxSpaces == gpu_data::kVisibleBoundsSpaces);

namespace {

// The float of a key of visible_bounds.comp (visibleBoundsKey: keys order as their floats).
float floatFromKey(uint32_t key) {
    const uint32_t bits = (key & 0x80000000u) != 0u ? key & 0x7fffffffu : ~key;
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
}

// The bins' spacing and spaces, with rsBounds sized for them (its elements left for the caller to fill).
void startBins(VisibleDepthBins& bins, float vsBinNear, float binsPerLogDepth, std::span<const glm::mat4> spaceFromWorld) {
    PENUMBRA_ASSERT(spaceFromWorld.size() <= VisibleDepthBins::kMaxSpaces);
    bins.vsBinNear = vsBinNear;
    bins.binsPerLogDepth = binsPerLogDepth;
    bins.spaceCount = uint32_t(spaceFromWorld.size());
    for (uint32_t space = 0; space < bins.spaceCount; ++space) bins.spaceFromWorld[space] = glm::mat3(spaceFromWorld[space]);
    bins.rsBounds.resize(size_t(bins.spaceCount) * VisibleDepthBins::kBins);
}

uint32_t binOf(const VisibleDepthBins& bins, float vsDepth) {
    return gpu_data::visibleDepthBin(vsDepth, bins.vsBinNear, bins.binsPerLogDepth);
}

// The bounds in space `space` of the bins that [vsNear, vsFar] meets, and one more bin on either side.
Aabb binnedBounds(const VisibleDepthBins& bins, uint32_t space, float vsNear, float vsFar) {
    Aabb bounds;
    if (!(vsNear <= vsFar)) return bounds;
    const uint32_t first = std::max(binOf(bins, vsNear), 1u) - 1u;
    const uint32_t last = std::min(binOf(bins, vsFar) + 1u, VisibleDepthBins::kBins - 1u);
    const Aabb* rsBins = bins.rsBounds.data() + size_t(space) * VisibleDepthBins::kBins;
    for (uint32_t bin = first; bin <= last; ++bin) bounds.extend(rsBins[bin]);
    return bounds;
}

Aabb binnedRotatedBounds(const VisibleDepthBins& bins, const glm::mat4& lightRotation, float vsNear, float vsFar) {
    if (bins.spaceCount == 0) return {};
    const glm::mat3 rotation(lightRotation);
    uint32_t closest = 0;
    float closestCosine = -2.0f;
    for (uint32_t space = 0; space < bins.spaceCount; ++space) {
        const glm::mat3& spaceFromWorld = bins.spaceFromWorld[space];
        if (spaceFromWorld == rotation) return binnedBounds(bins, space, vsNear, vsFar);
        // trace(R S^T) = 1 + 2 cos(the angle between the two rotations)
        const glm::mat3 relative = rotation * glm::transpose(spaceFromWorld);
        const float cosine = 0.5f * (relative[0][0] + relative[1][1] + relative[2][2] - 1.0f);
        if (cosine > closestCosine) {
            closestCosine = cosine;
            closest = space;
        }
    }
    const Aabb rsBounds = binnedBounds(bins, closest, vsNear, vsFar);
    if (!rsBounds.valid()) return rsBounds;
    return rsBounds.transformed(glm::mat4(rotation * glm::transpose(bins.spaceFromWorld[closest])));
}

}  // namespace

float visibleBinsPerLogDepth(float vsBinNear, float vsBinFar) {
    PENUMBRA_ASSERT(vsBinNear > 0.0f && vsBinFar > vsBinNear);
    return float(VisibleDepthBins::kBins) / std::log(vsBinFar / vsBinNear);
}

void visibleSurfacesFromBoundsWords(const uint32_t* words, float vsBinNear, float binsPerLogDepth,
                                    std::span<const glm::mat4> spaceFromWorld, VisibleSurfaces& visible) {
    const uint32_t* minima = words;
    const uint32_t* maxima = words + gpu_data::kVisibleBoundsMinWords;
    constexpr uint32_t kNone = 0xffffffffu;  // a minimum no surface lowered
    visible.wsPoints.clear();
    visible.vsDepths.clear();
    visible.vsMinDepth = minima[0] == kNone ? std::numeric_limits<float>::infinity() : floatFromKey(minima[0]);
    visible.vsMaxDepth = minima[0] == kNone ? 0.0f : floatFromKey(maxima[0]);
    VisibleDepthBins& bins = visible.bins;
    startBins(bins, vsBinNear, binsPerLogDepth, spaceFromWorld);
    for (size_t i = 0; i < bins.rsBounds.size(); ++i) {
        const uint32_t* lo = minima + 1 + i * 3;
        const uint32_t* hi = maxima + 1 + i * 3;
        bins.rsBounds[i] = lo[0] == kNone ? Aabb{}
                                          : Aabb{{floatFromKey(lo[0]), floatFromKey(lo[1]), floatFromKey(lo[2])},
                                                 {floatFromKey(hi[0]), floatFromKey(hi[1]), floatFromKey(hi[2])}};
    }
}

VisibleSurfaces binVisibleSurfaces(const VisibleSurfaces& points, std::span<const glm::mat4> spaceFromWorld,
                                   float vsBinNear, float vsBinFar) {
    VisibleSurfaces binned;
    binned.vsMinDepth = points.vsMinDepth;
    binned.vsMaxDepth = points.vsMaxDepth;
    VisibleDepthBins& bins = binned.bins;
    startBins(bins, vsBinNear, visibleBinsPerLogDepth(vsBinNear, vsBinFar), spaceFromWorld);  // every bin empty
    for (size_t i = 0; i < points.wsPoints.size(); ++i) {
        const uint32_t bin = binOf(bins, points.vsDepths[i]);
        for (uint32_t space = 0; space < bins.spaceCount; ++space)
            bins.rsBounds[size_t(space) * VisibleDepthBins::kBins + bin].extend(bins.spaceFromWorld[space] * points.wsPoints[i]);
    }
    return binned;
}

VisibleSurfaces visibleSurfacesFromDepth(const Image& depth, const CameraView& view) {
    PENUMBRA_ASSERT(depth.channels == 4 && depth.width == view.width && depth.height == view.height);
    VisibleSurfaces visible;
    visible.wsPoints.reserve(size_t(depth.width) * depth.height);
    visible.vsDepths.reserve(size_t(depth.width) * depth.height);
    forEachSurfacePixel(depth, view, [&](const glm::vec3& wsPoint, float vsDepth) {
        visible.wsPoints.push_back(wsPoint);
        visible.vsDepths.push_back(vsDepth);
        visible.vsMinDepth = std::min(visible.vsMinDepth, vsDepth);
        visible.vsMaxDepth = std::max(visible.vsMaxDepth, vsDepth);
    });
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
    if (visible.wsPoints.empty()) return binnedRotatedBounds(visible.bins, lightRotation, vsNear, vsFar);
    const glm::mat3 rotation(lightRotation);
    Aabb bounds;
    for (size_t i = 0; i < visible.wsPoints.size(); ++i) {
        if (visible.vsDepths[i] < vsNear || visible.vsDepths[i] > vsFar) continue;
        bounds.extend(rotation * visible.wsPoints[i]);
    }
    return bounds;
}

}  // namespace penumbra
