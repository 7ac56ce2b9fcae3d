#pragma once
// Cached shadow tiles (shadows.cacheTiles; Godot's shadow atlas and UE5's virtual shadow map pages do
// the same): a tile whose projection, viewport, caster set and rasterizer did not change since the
// last frame keeps last frame's depth and is not drawn again. Cascades follow the camera, so they
// stay cached while their texel-snapped projection and the cascade spheres (blend culling) stand
// still; spot and point tiles stay cached while their light does. No GPU here: unit-tested.
#include <array>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// Everything that decides the depth a tile holds, as numbers to compare; held inline (no heap): the
// projection (16), viewport and scissor (4), bias (1), and for a directional tile the cascade spheres
// (4 x 4), the blend culling factor (1), the receiver bounds (6) and the receiver volume (8 x 4).
struct TileSignature {
    static constexpr uint32_t kCapacity = 16 + 4 + 1 + 4 * 4 + 1 + 6 + 8 * 4;
    std::array<float, kCapacity> values{};  // unused values stay 0
    uint32_t size = 0;

    void push_back(float value) {
        PENUMBRA_ASSERT(size < kCapacity);
        values[size++] = value;
    }
    bool operator==(const TileSignature&) const = default;
};

// The signature of a directional tile includes the plan's cascade spheres, blend culling factor and
// the tile's receiver volume (which decide its casters); of a spot/point tile, its projection alone.
TileSignature directionalTileSignature(const ShadowTile& tile, const DirectionalShadowPlan& plan);
TileSignature otherTileSignature(const ShadowTile& tile);

class TileCache {
public:
    // The tiles (indices into `tiles`) to draw this frame; the others keep their depth. Everything is
    // drawn when the atlas was re-made (`atlasGeneration` changed), the rasterizer changed, the scene's
    // casters changed (`sceneVersion`), or caching is off.
    // `draw` is cleared and refilled (its capacity is kept).
    void tilesToDraw(const std::vector<TileSignature>& tiles, uint64_t atlasGeneration, bool compute,
                     uint64_t sceneVersion, bool enabled, std::vector<uint32_t>& draw);
    std::vector<uint32_t> tilesToDraw(const std::vector<TileSignature>& tiles, uint64_t atlasGeneration, bool compute,
                                      uint64_t sceneVersion, bool enabled) {
        std::vector<uint32_t> draw;
        tilesToDraw(tiles, atlasGeneration, compute, sceneVersion, enabled, draw);
        return draw;
    }
    // Whether the last tilesToDraw kept some tiles (the atlas must then be loaded, not cleared).
    bool reusedAny() const { return reused_ > 0; }
    // The next tilesToDraw draws every tile (what was drawn is incomplete, e.g. an overflowed queue).
    void invalidate() { last_.clear(); }
    uint32_t reused() const { return reused_; }

private:
    std::vector<TileSignature> last_;
    uint64_t atlasGeneration_ = ~0ull, sceneVersion_ = ~0ull;
    bool compute_ = false;
    uint32_t reused_ = 0;
};

}  // namespace penumbra
