#include "shadows/cascades.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace penumbra {

float shadowDistance(const CameraView& camera, float maxDistance) {
    const float zFar = std::isfinite(camera.zFar) && camera.zFar > 0.0f ? camera.zFar : maxDistance;
    return std::max(std::min(maxDistance, zFar), camera.zNear);
}

CascadeSphere frustumSliceSphere(const CameraView& camera, float vsNear, float vsFar) {
    const float tanHalfY = std::tan(0.5f * camera.yfov);
    const float tanHalfX = tanHalfY * camera.aspect;
    const float k2 = tanHalfX * tanHalfX + tanHalfY * tanHalfY;
    const float center = std::min(vsFar, 0.5f * (vsNear + vsFar) * (1.0f + k2));
    // Distance to the far ring; the near ring is at the same distance or closer by construction.
    const float dz = vsFar - center;
    CascadeSphere sphere;
    sphere.vsNear = vsNear;
    sphere.vsFar = vsFar;
    sphere.radius = std::sqrt(dz * dz + k2 * vsFar * vsFar);
    sphere.wsCenter = camera.wsPosition + glm::normalize(camera.wsForward) * center;
    return sphere;
}

namespace {

// At most 4 cascades (validateShadowSettings): the splits fit in an array, no heap.
struct CascadeSplits {
    std::array<float, 4> vsFar{};
    uint32_t count = 0;
};

CascadeSplits ratioSplits(const CameraView& camera, float distance, uint32_t cascadeCount,
                          const std::array<float, 3>& ratios) {
    PENUMBRA_ASSERT(cascadeCount >= 1 && cascadeCount <= 4);
    CascadeSplits splits;
    splits.count = cascadeCount;
    float previous = camera.zNear;
    for (uint32_t i = 0; i + 1 < cascadeCount; ++i) {
        // Settings validation refuses decreasing ratios; the clamp also keeps every split within
        // [zNear, distance] when the near plane lies beyond the first ratio's distance.
        splits.vsFar[i] = std::clamp(ratios[i] * distance, previous, distance);
        previous = splits.vsFar[i];
    }
    splits.vsFar[cascadeCount - 1] = distance;
    return splits;
}

CascadeSplits splitsOf(const CameraView& camera, float vsNear, float vsFar, const DirectionalShadowSettings& settings,
                       float shadowDistance) {
    const uint32_t count = settings.cascadeCount;
    PENUMBRA_ASSERT(count >= 1 && count <= 4);
    if (settings.cascadeSplits == CascadeSplitMode::Manual) {
        CascadeSplits splits = ratioSplits(camera, shadowDistance, count, settings.cascadeRatios);
        const float last = std::max(std::min(vsFar, shadowDistance), camera.zNear);
        splits.vsFar[count - 1] = last;
        for (uint32_t i = 0; i < count; ++i) splits.vsFar[i] = std::min(splits.vsFar[i], last);
        return splits;
    }
    CascadeSplits splits;
    splits.count = count;
    const float n = std::max(vsNear, camera.zNear), f = std::max(vsFar, n * 1.0001f);
    const float lambda = settings.cascadeSplits == CascadeSplitMode::Log ? 1.0f : settings.splitLambda;
    for (uint32_t i = 1; i <= count; ++i) {
        const float t = float(i) / float(count);
        const float logSplit = n * std::pow(f / n, t);
        const float uniformSplit = n + (f - n) * t;
        splits.vsFar[i - 1] = lambda * logSplit + (1.0f - lambda) * uniformSplit;
    }
    splits.vsFar[count - 1] = f;
    return splits;
}

}  // namespace

std::vector<float> cascadeSplitDistances(const CameraView& camera, float distance, uint32_t cascadeCount,
                                         const std::array<float, 3>& ratios) {
    const CascadeSplits splits = ratioSplits(camera, distance, cascadeCount, ratios);
    return std::vector<float>(splits.vsFar.begin(), splits.vsFar.begin() + splits.count);
}

std::vector<float> cascadeSplitDistances(const CameraView& camera, float vsNear, float vsFar,
                                         const DirectionalShadowSettings& settings, float shadowDistance) {
    const CascadeSplits splits = splitsOf(camera, vsNear, vsFar, settings, shadowDistance);
    return std::vector<float>(splits.vsFar.begin(), splits.vsFar.begin() + splits.count);
}

void computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings, float vsNear, float vsFar,
                           std::vector<CascadeSphere>& spheres) {
    const float distance = shadowDistance(camera, settings.maxDistance);
    const CascadeSplits splits = splitsOf(camera, vsNear, std::min(vsFar, distance), settings.directional, distance);
    spheres.clear();
    float sliceNear = camera.zNear;
    for (uint32_t i = 0; i < splits.count; ++i) {
        spheres.push_back(frustumSliceSphere(camera, sliceNear, splits.vsFar[i]));
        sliceNear = splits.vsFar[i];
    }
}

std::vector<CascadeSphere> computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings,
                                                 float vsNear, float vsFar) {
    std::vector<CascadeSphere> spheres;
    computeCascadeSpheres(camera, settings, vsNear, vsFar, spheres);
    return spheres;
}

std::vector<CascadeSphere> computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings) {
    return computeCascadeSpheres(camera, settings, camera.zNear, shadowDistance(camera, settings.maxDistance));
}

glm::mat4 lightRotationFromWorld(const glm::vec3& wsDirection) {
    const glm::vec3 forward = glm::normalize(wsDirection);
    // Any fixed up vector works as long as it is the same every frame; avoid the degenerate one.
    const glm::vec3 up = std::abs(forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 lsUp = glm::cross(right, forward);
    glm::mat4 m(1.0f);  // rows = light axes: x = right, y = up, z = -forward
    m[0][0] = right.x;  m[1][0] = right.y;  m[2][0] = right.z;
    m[0][1] = lsUp.x;   m[1][1] = lsUp.y;   m[2][1] = lsUp.z;
    m[0][2] = -forward.x; m[1][2] = -forward.y; m[2][2] = -forward.z;
    return m;
}

namespace {

// The light view centred on rsCenter (light rotation space) rounded to whole texels in x and y: world
// geometry keeps its sub-texel position while the centre moves, so static shadows don't shimmer.
// Round (not floor): the fitted region sticks out of the box by at most half a texel, which the
// margins (the sphere's filter-size shrink; the tight box's texels) more than cover.
CascadeLightView snappedLightView(const glm::mat4& lightRotation, const glm::vec3& rsCenter, float halfExtent,
                                  uint32_t tileSize) {
    CascadeLightView view;
    view.halfExtent = halfExtent;
    view.wsTexelSize = 2.0f * halfExtent / float(tileSize);
    glm::vec3 snapped = rsCenter;
    if (view.wsTexelSize > 0.0f) {
        snapped.x = std::floor(rsCenter.x / view.wsTexelSize + 0.5f) * view.wsTexelSize;
        snapped.y = std::floor(rsCenter.y / view.wsTexelSize + 0.5f) * view.wsTexelSize;
    }
    glm::mat4 translation(1.0f);
    translation[3] = glm::vec4(-snapped, 1.0f);
    view.lightFromWorld = translation * lightRotation;
    view.lsSphereCenter = rsCenter - snapped;
    return view;
}

}  // namespace

CascadeLightView fitCascadeLightView(const glm::mat4& lightRotation, const CascadeSphere& sphere,
                                     uint32_t tileSize) {
    PENUMBRA_ASSERT(tileSize > 0);
    const glm::vec3 rsCenter = glm::vec3(lightRotation * glm::vec4(sphere.wsCenter, 1.0f));
    CascadeLightView view = snappedLightView(lightRotation, rsCenter, sphere.radius, tileSize);
    view.receiversNear = sphere.radius + view.lsSphereCenter.z;
    view.receiversFar = sphere.radius - view.lsSphereCenter.z;
    return view;
}

float quantizedHalfExtent(float halfExtent) {
    PENUMBRA_ASSERT(halfExtent > 0.0f);
    return std::exp2(std::ceil(std::log2(halfExtent) * 8.0f - 1e-4f) / 8.0f);
}

CascadeLightView fitTightLightView(const glm::mat4& lightRotation, const Aabb& rsBounds, uint32_t tileSize,
                                   float marginTexels) {
    PENUMBRA_ASSERT(tileSize > 0 && rsBounds.valid() && 2.0f * marginTexels < float(tileSize));
    const glm::vec3 extent = rsBounds.extent();
    // h grown by marginTexels texels of its own size: h' = h + marginTexels * 2 h' / tileSize.
    const float half = std::max(0.5f * std::max(extent.x, extent.y), 1e-4f);
    const float halfExtent = quantizedHalfExtent(half / (1.0f - 2.0f * marginTexels / float(tileSize)));
    CascadeLightView view = snappedLightView(lightRotation, rsBounds.center(), halfExtent, tileSize);
    // lsSphereCenter.z is 0 (z is not snapped): the box's z faces lie at +- extent.z / 2 around it.
    view.receiversNear = 0.5f * extent.z + marginTexels * view.wsTexelSize;
    view.receiversFar = 0.5f * extent.z + marginTexels * view.wsTexelSize;
    return view;
}

glm::mat4 orthoClipFromLight(float halfExtent, float nearDistance, float farDistance) {
    PENUMBRA_ASSERT(halfExtent > 0.0f && nearDistance + farDistance > 0.0f);
    const float depthRange = nearDistance + farDistance;
    glm::mat4 m(0.0f);
    m[0][0] = 1.0f / halfExtent;
    m[1][1] = -1.0f / halfExtent;  // Vulkan NDC y points down: light-space up -> top of the tile
    m[2][2] = -1.0f / depthRange;
    m[3][2] = nearDistance / depthRange;
    m[3][3] = 1.0f;
    return m;
}

}  // namespace penumbra
