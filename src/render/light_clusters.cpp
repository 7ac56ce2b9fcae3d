#include "render/light_clusters.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

using gpu_data::kClusterBoundsMargin;
using gpu_data::kClusterSlices;
using gpu_data::kClusterTilesX;
using gpu_data::kClusterTilesY;

// The view-space point at view depth vsDepth on the ray through NDC (x, y).
glm::vec3 viewPointAtDepth(const glm::mat4& viewFromClip, float ndcX, float ndcY, float vsDepth) {
    glm::vec4 p = viewFromClip * glm::vec4(ndcX, ndcY, 0.5f, 1.0f);
    const glm::vec3 onRay = glm::vec3(p) / p.w;
    return onRay * (vsDepth / -onRay.z);
}

// The start of a slice in view depth: near * (far / near)^(slice / slices).
float sliceDepth(const gpu_data::LightClusterData& clusters, uint32_t slice) {
    return clusters.nearDepth * std::exp(float(slice) / clusters.slicesPerLogDepth);
}

}  // namespace

float clusterFarDepth(const CameraView& view, const Aabb& wsSceneBounds) {
    float far = std::isfinite(view.zFar) && view.zFar > view.zNear ? view.zFar : 0.0f;
    if (far == 0.0f && wsSceneBounds.valid()) {
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 ws((corner & 1) ? wsSceneBounds.max.x : wsSceneBounds.min.x,
                               (corner & 2) ? wsSceneBounds.max.y : wsSceneBounds.min.y,
                               (corner & 4) ? wsSceneBounds.max.z : wsSceneBounds.min.z);
            far = std::max(far, -(view.viewFromWorld * glm::vec4(ws, 1.0f)).z);
        }
        far *= 1.0f + 4.0f * kClusterBoundsMargin;
    }
    return std::max(far, 2.0f * view.zNear);
}

gpu_data::LightClusterData makeLightClusterData(const CameraView& view, const Aabb& wsSceneBounds, uint32_t firstOther,
                                                uint32_t otherCount, bool clustered) {
    gpu_data::LightClusterData clusters{};
    clusters.viewFromClip = glm::inverse(view.clipFromView);
    clusters.viewFromWorld = view.viewFromWorld;
    const float near = view.zNear, far = clusterFarDepth(view, wsSceneBounds);
    clusters.nearDepth = near;
    clusters.farDepth = far;
    clusters.slicesPerLogDepth = float(kClusterSlices) / std::log(far / near);
    clusters.tilesPerPixel = glm::vec2(float(kClusterTilesX) / float(view.width), float(kClusterTilesY) / float(view.height));
    clusters.viewSize = glm::vec2(float(view.width), float(view.height));
    clusters.lightCount = otherCount;
    clusters.firstLight = firstOther;
    clusters.wordsPerCluster = (otherCount + 31u) / 32u;
    clusters.clustered = clustered && otherCount > 0 ? 1u : 0u;
    return clusters;
}

ViewBox clusterViewBox(const gpu_data::LightClusterData& clusters, uint32_t tileX, uint32_t tileY, uint32_t slice) {
    // The tile's pixel rectangle in NDC (Vulkan: pixel 0 at NDC -1 in x and y), and its depth range.
    const float x0 = 2.0f * float(tileX) / float(kClusterTilesX) - 1.0f, x1 = 2.0f * float(tileX + 1) / float(kClusterTilesX) - 1.0f;
    const float y0 = 2.0f * float(tileY) / float(kClusterTilesY) - 1.0f, y1 = 2.0f * float(tileY + 1) / float(kClusterTilesY) - 1.0f;
    const float d0 = sliceDepth(clusters, slice) * (1.0f - kClusterBoundsMargin);
    const float d1 = sliceDepth(clusters, slice + 1) * (1.0f + kClusterBoundsMargin);
    ViewBox box{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p = viewPointAtDepth(clusters.viewFromClip, (corner & 1) ? x1 : x0, (corner & 2) ? y1 : y0,
                                             (corner & 4) ? d1 : d0);
        box.vsMin = glm::min(box.vsMin, p);
        box.vsMax = glm::max(box.vsMax, p);
    }
    const glm::vec3 grow = kClusterBoundsMargin * glm::max(glm::abs(box.vsMin), glm::abs(box.vsMax));
    box.vsMin -= grow;
    box.vsMax += grow;
    return box;
}

bool lightTouchesViewBox(const gpu_data::LightData& light, const glm::mat4& viewFromWorld, const ViewBox& box) {
    const glm::vec3 vsLight = glm::vec3(viewFromWorld * glm::vec4(light.wsPosition, 1.0f));
    const float inverseRangeSquared = light.invRangeSquared;
    const bool ranged = inverseRangeSquared > 0.0f;
    const float range = ranged ? (1.0f + kClusterBoundsMargin) / std::sqrt(inverseRangeSquared) : 0.0f;
    if (ranged) {  // the range sphere against the box
        const glm::vec3 closest = glm::clamp(vsLight, box.vsMin, box.vsMax);
        const glm::vec3 offset = closest - vsLight;
        if (glm::dot(offset, offset) > range * range) return false;
    }
    if (light.type != gpu_data::kLightSpot) return true;
    // The cone (outer angle, grown) against the box's bounding sphere (Wronski's cone test): a lower
    // bound of the distance from the sphere's centre to the cone.
    const glm::vec3 vsAxis = glm::normalize(glm::mat3(viewFromWorld) * -light.wsToLight);
    const float cosOuter = std::clamp(-light.spotOffset / light.spotScale, -1.0f, 1.0f);
    const float angle = std::min(std::acos(cosOuter) * (1.0f + kClusterBoundsMargin) + kClusterBoundsMargin, 3.14159265f);
    const glm::vec3 center = 0.5f * (box.vsMin + box.vsMax);
    const float radius = 0.5f * glm::length(box.vsMax - box.vsMin);
    const glm::vec3 v = center - vsLight;
    const float along = glm::dot(v, vsAxis);
    const float across = std::sqrt(std::max(glm::dot(v, v) - along * along, 0.0f));
    if (std::cos(angle) * across - along * std::sin(angle) > radius) return false;
    if (angle < 0.5f * 3.14159265f && along < -radius) return false;  // wholly behind the light
    return !(ranged && along > radius + range);
}

int32_t clusterOfPixel(const gpu_data::LightClusterData& clusters, const glm::vec2& pixel, float vsDepth) {
    if (!(vsDepth <= clusters.farDepth)) return -1;
    const float slice = std::floor(std::log(std::max(vsDepth, clusters.nearDepth) / clusters.nearDepth) * clusters.slicesPerLogDepth);
    const uint32_t z = std::min(uint32_t(std::max(slice, 0.0f)), kClusterSlices - 1);
    const uint32_t x = std::min(uint32_t(pixel.x * clusters.tilesPerPixel.x), kClusterTilesX - 1);
    const uint32_t y = std::min(uint32_t(pixel.y * clusters.tilesPerPixel.y), kClusterTilesY - 1);
    return int32_t((z * kClusterTilesY + y) * kClusterTilesX + x);
}

std::vector<uint32_t> clusterLightMasks(const gpu_data::LightClusterData& clusters,
                                        const std::vector<gpu_data::LightData>& lights) {
    const uint32_t words = clusters.wordsPerCluster;
    std::vector<uint32_t> masks(size_t(gpu_data::kClusterCount) * words, 0u);
    for (uint32_t slice = 0; slice < kClusterSlices; ++slice)
        for (uint32_t y = 0; y < kClusterTilesY; ++y)
            for (uint32_t x = 0; x < kClusterTilesX; ++x) {
                const ViewBox box = clusterViewBox(clusters, x, y, slice);
                const size_t cluster = (size_t(slice) * kClusterTilesY + y) * kClusterTilesX + x;
                for (uint32_t i = 0; i < clusters.lightCount; ++i)
                    if (lightTouchesViewBox(lights.at(clusters.firstLight + i), clusters.viewFromWorld, box))
                        masks[cluster * words + i / 32] |= 1u << (i % 32);
            }
    return masks;
}

}  // namespace penumbra
