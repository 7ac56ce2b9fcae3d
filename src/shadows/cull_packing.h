#pragma once
// The shadow tiles of a plan as the GPU culling pass reads them (cull_structs.h): per tile the same
// volume the CPU culling tests (shadows/caster_culling.h for cascades, shadows/spot_culling.h for
// spot and point faces), the cascade spheres and the receivers' bounds for blend culling. Pure CPU.
#include <cstdint>
#include <vector>

#include "cull_structs.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// Directional tiles first, then the spot/point tiles: culling tile i of the frame is
// frame.directional.tiles[i] for i < directional tile count, else frame.other.tiles[i - that count].
// Throws Error (internal) when the plan has more than kMaxCullTiles tiles.
gpu_data::CullFrame packCullFrame(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount);
// Sets CullFrame::rasterTiles to `tiles` (culling tile indices, at most kMaxCullTiles).
void packRasterTiles(gpu_data::CullFrame& frame, const std::vector<uint32_t>& tiles);

}  // namespace penumbra
