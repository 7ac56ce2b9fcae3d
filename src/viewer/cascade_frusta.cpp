#include "viewer/cascade_frusta.h"

#include <algorithm>
#include <array>
#include <cmath>


#include "penumbra/scene_builder.h"

namespace penumbra::viewer {

CascadeGeometry cascadeGeometry(const ShadowPlanStats& shadows) {
    CascadeGeometry geometry;
    const DirectionalShadowStats& directional = shadows.directional;
    geometry.wsCullingSpheres.assign(directional.cullingSpheres.begin(), directional.cullingSpheres.end());
    for (const DirectionalTileStats& tile : directional.tileStats) geometry.boxes.push_back({tile.cascade, tile.worldFromClip});
    if (!directional.cascadeSplits.empty()) geometry.shadowDistance = directional.cascadeSplits.back();
    return geometry;
}

namespace {

// Corner i of a box: bit 0 picks x, bit 1 y, bit 2 depth.
glm::vec3 boxCorner(const glm::mat4& worldFromClip, int i) {
    const glm::vec4 clip(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : 0.0f, 1.0f);
    const glm::vec4 world = worldFromClip * clip;
    return glm::vec3(world) / world.w;
}

// The 12 edges of a cube whose corners are numbered as boxCorner's.
constexpr std::array<std::pair<int, int>, 12> kCubeEdges = {
    {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};

void addBox(std::vector<WorldLine>& lines, const std::array<glm::vec3, 8>& corners, LineKind kind, uint32_t cascade) {
    for (const auto& [a, b] : kCubeEdges) lines.push_back({corners[size_t(a)], corners[size_t(b)], kind, cascade});
}

void addSphere(std::vector<WorldLine>& lines, const glm::vec4& sphere, uint32_t cascade) {
    const glm::vec3 centre(sphere);
    const float r = sphere.w;
    const std::array<std::pair<glm::vec3, glm::vec3>, 3> planes = {
        {{{1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}}}};
    for (const auto& [u, v] : planes)
        for (uint32_t s = 0; s < kSphereSegments; ++s) {
            const float a0 = 6.2831853f * float(s) / float(kSphereSegments);
            const float a1 = 6.2831853f * float(s + 1) / float(kSphereSegments);
            lines.push_back({centre + r * (std::cos(a0) * u + std::sin(a0) * v),
                             centre + r * (std::cos(a1) * u + std::sin(a1) * v), LineKind::Sphere, cascade});
        }
}

}  // namespace

std::vector<WorldLine> cascadeLines(const CascadeGeometry& geometry, const CameraView& observed) {
    std::vector<WorldLine> lines;
    for (const CascadeGeometry::Box& box : geometry.boxes) {
        std::array<glm::vec3, 8> corners;
        for (int i = 0; i < 8; ++i) corners[size_t(i)] = boxCorner(box.worldFromClip, i);
        addBox(lines, corners, LineKind::Box, box.cascade);
    }
    for (size_t i = 0; i < geometry.wsCullingSpheres.size(); ++i) addSphere(lines, geometry.wsCullingSpheres[i], uint32_t(i));
    if (geometry.shadowDistance > observed.zNear) {
        // The observed frustum: view-space corners at the near plane and at the shadow distance.
        const float tanY = std::tan(observed.yfov * 0.5f), tanX = tanY * observed.aspect;
        std::array<glm::vec3, 8> corners;
        for (int i = 0; i < 8; ++i) {
            const float depth = i & 4 ? geometry.shadowDistance : observed.zNear;
            const glm::vec4 vs((i & 1 ? 1.0f : -1.0f) * tanX * depth, (i & 2 ? 1.0f : -1.0f) * tanY * depth, -depth, 1.0f);
            corners[size_t(i)] = glm::vec3(observed.worldFromView * vs);
        }
        addBox(lines, corners, LineKind::ObservedFrustum, 0);
    }
    return lines;
}

std::optional<std::pair<glm::vec2, glm::vec2>> projectToPixels(const CameraView& view, const glm::vec3& wsFrom,
                                                              const glm::vec3& wsTo) {
    glm::vec4 a = view.clipFromWorld * glm::vec4(wsFrom, 1.0f), b = view.clipFromWorld * glm::vec4(wsTo, 1.0f);
    const float nearW = view.zNear;  // clip w is the view depth
    if (a.w < nearW && b.w < nearW) return std::nullopt;
    if (a.w < nearW) a = glm::mix(a, b, (nearW - a.w) / (b.w - a.w));
    if (b.w < nearW) b = glm::mix(b, a, (nearW - b.w) / (a.w - b.w));
    auto pixels = [&](const glm::vec4& clip) {
        return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * float(view.width), (clip.y / clip.w * 0.5f + 0.5f) * float(view.height));
    };
    return std::make_pair(pixels(a), pixels(b));
}

Camera outsideCamera(const Camera& observed, float distance) {
    const glm::vec3 wsEye(observed.worldFromView[3]), wsForward = -glm::vec3(observed.worldFromView[2]);
    const glm::vec3 wsUp(observed.worldFromView[1]), wsRight(observed.worldFromView[0]);
    const glm::vec3 wsTarget = wsEye + wsForward * (0.5f * distance);
    const glm::vec3 wsOutside = wsTarget + distance * (-0.9f * wsForward + 0.7f * wsUp + 0.6f * wsRight);
    Camera camera = makeLookAtCamera(wsOutside, wsTarget, observed.yfov, std::max(0.01f, 0.01f * distance));
    camera.name = "outside";
    return camera;
}

}  // namespace penumbra::viewer
