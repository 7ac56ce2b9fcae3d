#pragma once
// The "frusta" view: the directional cascades of one camera (the observed camera, frozen when the view
// is entered) seen from an outside camera, drawn as lines over the image: each tile's light-space box
// (the cascade's shadow frustum), each cascade's culling sphere as a wire sphere (three great circles)
// and the observed camera's frustum out to the shadow distance. Pure CPU (the ImGui drawing is in
// panels.cpp), so the geometry is unit-tested.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/shadow_stats.h"

namespace penumbra::viewer {

// What a frame's shadow stats (RenderResult::stats.shadows.directional) say of the cascades.
struct CascadeGeometry {
    std::vector<glm::vec4> wsCullingSpheres;  // centre, radius; one per cascade
    struct Box {
        uint32_t cascade = 0;
        glm::mat4 worldFromClip{1.0f};  // the tile's clip cube (x, y in [-1, 1], depth in [0, 1]) in world space
    };
    std::vector<Box> boxes;  // one per tile: every shadowed directional light's cascades
    float shadowDistance = 0.0f;  // view depth where the last cascade ends
};
CascadeGeometry cascadeGeometry(const ShadowPlanStats& shadows);

enum class LineKind { Box, Sphere, ObservedFrustum };
struct WorldLine {
    glm::vec3 wsFrom{0.0f}, wsTo{0.0f};
    LineKind kind = LineKind::Box;
    uint32_t cascade = 0;  // Box, Sphere
};
inline constexpr uint32_t kSphereSegments = 48;  // per great circle

// 12 edges per box, 3 x kSphereSegments per sphere, 12 edges for the observed frustum (its corners at
// the near plane and at the shadow distance).
std::vector<WorldLine> cascadeLines(const CascadeGeometry& geometry, const CameraView& observed);

// The segment in pixels of `view` (y down, like its image), clipped to its near plane; nullopt when the
// segment lies wholly behind it.
std::optional<std::pair<glm::vec2, glm::vec2>> projectToPixels(const CameraView& view, const glm::vec3& wsFrom,
                                                              const glm::vec3& wsTo);

// A camera behind, above and to the right of `observed` that looks at the middle of its first
// `distance` metres, far enough back to see them all.
Camera outsideCamera(const Camera& observed, float distance);

}  // namespace penumbra::viewer
