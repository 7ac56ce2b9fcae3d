#pragma once
// The shadow tiles of a plan as the GPU culling pass reads them (cull_structs.h): per tile the same
// volume the CPU culling tests (shadows/caster_culling.h for cascades, shadows/spot_culling.h for
// spot and point faces), the cascade spheres and the receivers' bounds for blend culling. Pure CPU.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "cull_structs.h"
#include "penumbra/render_settings.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// Directional tiles first, then the spot/point tiles: culling tile i of the frame is
// frame.directional.tiles[i] for i < directional tile count, else frame.other.tiles[i - that count].
// Throws Error (internal) when the plan has more than kMaxCullTiles tiles.
gpu_data::CullFrame packCullFrame(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount);
// Sets CullFrame::rasterTiles to `tiles` (culling tile indices, at most kMaxCullTiles).
void packRasterTiles(gpu_data::CullFrame& frame, const std::vector<uint32_t>& tiles);

// The main view's depth pyramid (cull_structs.h CullCamera): level 0 is half the view rounded up,
// each next level half the one below rounded up, down to 1 x 1; the levels lie one after the other.
struct DepthPyramidLayout {
    std::vector<glm::uvec2> sizes;
    std::vector<uint32_t> offsets;  // first texel of each level
    uint32_t texels = 0;            // all levels
};
DepthPyramidLayout depthPyramidLayout(uint32_t width, uint32_t height);
// Its level count alone, without building the layout (no allocation: packed every frame).
uint32_t depthPyramidLevelCount(uint32_t width, uint32_t height);

// The camera the main view's culling tests (CullFrame::camera).
gpu_data::CullCamera packCullCamera(const glm::mat4& clipFromWorld, uint32_t width, uint32_t height, ViewCulling culling);

}  // namespace penumbra
