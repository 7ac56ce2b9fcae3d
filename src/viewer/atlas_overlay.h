#pragma once
// The shadow atlases' tile labels (--view atlas): the depth the renderer read back (the directional
// atlas left, the spot/point atlas right, as penumbra render --dump-atlas writes them) is shown by an
// ImageOverlay in the bottom-left of the window, each tile labelled with its light and cascade or cube face.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "penumbra/shadow_stats.h"

namespace penumbra::viewer {

// A tile of the atlas image in its pixels, with its label naming the scene light (its index in
// Scene::lights, as --light, the inspector and the stats JSON count) and the cascade or cube face:
// "sun1 c2" (light 1, cascade 2), "spot2", "point3 +X".
struct AtlasTileLabel {
    glm::vec2 min{0.0f}, max{0.0f};
    std::string text;
};

// The tiles of both atlases from a frame's shadow stats (FrameStats::shadows).
std::vector<AtlasTileLabel> atlasTileLabels(const ShadowPlanStats& shadows, const Scene& scene);

}  // namespace penumbra::viewer
