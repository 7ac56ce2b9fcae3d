#pragma once
// The shadow tiles of a plan as the GPU culling pass reads them (cull_structs.h): per tile the same
// volume the CPU culling tests (shadows/caster_culling.h for cascades, shadows/spot_culling.h for
// spot and point faces), the cascade spheres and the receivers' bounds for blend culling. Pure CPU.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cull_structs.h"
#include "penumbra/render_settings.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// The spheres, receiver bounds and counts every culling dispatch reads (the camera: packCullCamera).
gpu_data::CullFrame packCullFrame(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount);

// The atlases' tiles as a culling tile list (cull_structs.h CullTileListHeader), the CPU's side of the
// lists the GPU writes for the virtual pages: uploaded as they are (bytes() of them) each frame.
struct CullTileUpload {
    gpu_data::CullTileListHeader header{};
    std::array<gpu_data::CullTile, gpu_data::kMaxCullTiles> tiles{};
    size_t bytes() const;  // the header and the used records (at least one: a valid binding range)
};
// The entries one atlas pass of the compute rasterizer draws (RasterTileListHeader + culling tile indices).
struct RasterTileUpload {
    gpu_data::RasterTileListHeader header{};
    std::array<uint32_t, gpu_data::kMaxCullTiles> entries{};
    size_t bytes() const;
};
// Directional tiles first, then the spot/point tiles: culling tile i of the frame is
// frame.directional.tiles[i] for i < directional tile count, else frame.other.tiles[i - that count];
// the dispatch sizes for instanceCount instances and meshCount meshes. Throws Error (internal) when the
// plan has more than kMaxCullTiles tiles.
void packCullTiles(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount, CullTileUpload& out);
// The tiles `drawn` (indices into `tiles`, whose culling tiles start at firstCullTile) of one atlas pass,
// with its clear dispatch (the largest drawn tile) and work-item expansion dispatch (instanceCount
// slots of each tile's culled list).
void packRasterTiles(const std::vector<ShadowTile>& tiles, std::span<const uint32_t> drawn, uint32_t firstCullTile,
                     uint32_t instanceCount, RasterTileUpload& out);
// The compute rasterizer's expansion dispatch (shadow_raster_expand.comp): the slots of instanceCount
// instances (at least one group) for `tiles` tiles in z.
glm::uvec4 rasterExpandDispatch(uint32_t instanceCount, uint32_t tiles);

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
