#pragma once
// The shadow plan of one frame as plain data (FrameStats::shadows): the lights each atlas reserved,
// its tiles, and the casters and triangles drawn per tile. Every list has a fixed capacity set by the
// renderer's limits (4 shadowed directional lights x 4 cascades, 16 spot/point tiles), so a frame
// builds its stats without touching the heap; toJson() writes them as `penumbra render --stats` and
// `penumbra bench` print them ("shadows"), only when a caller asks.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace penumbra {

// At most Capacity values, held inline.
template <typename T, uint32_t Capacity>
class InlineList {
public:
    static constexpr uint32_t capacity() { return Capacity; }
    uint32_t size() const { return count_; }
    bool empty() const { return count_ == 0; }
    const T* begin() const { return items_; }
    const T* end() const { return items_ + count_; }
    T* begin() { return items_; }
    T* end() { return items_ + count_; }
    const T& operator[](uint32_t i) const { return items_[i]; }
    T& operator[](uint32_t i) { return items_[i]; }
    const T& back() const { return items_[count_ - 1]; }
    void clear() { count_ = 0; }
    // Appends `value`; a full list keeps what it has and returns false.
    bool push_back(const T& value) {
        if (count_ == Capacity) return false;
        items_[count_++] = value;
        return true;
    }

private:
    T items_[Capacity]{};
    uint32_t count_ = 0;
};

// What one tile's depth pass drew.
struct ShadowTileDraws {
    uint32_t casters = 0;    // caster instances: the GPU culling's count, else the plan's CPU list
    uint64_t triangles = 0;  // their triangles, when the atlas's trianglesCounted
};

struct DirectionalTileStats {
    uint32_t light = 0;    // the light's slot (an index into DirectionalShadowStats::reservedLights)
    uint32_t cascade = 0;
    ShadowTileDraws drawn;
    float depthRangeMetres = 0.0f;     // near + far distance of the tile's depth range
    float pancakedDepthMetres = 0.0f;  // how far casters reach in front of the near plane
    float texelSizeMetres = 0.0f;      // world size of one texel
    glm::mat4 worldFromClip{1.0f};     // the tile's box (clip x, y in [-1, 1], depth in [0, 1])
};

struct DirectionalShadowStats {
    static constexpr uint32_t kMaxLights = 4, kMaxCascades = 4, kMaxTiles = kMaxLights * kMaxCascades;
    uint32_t lightsConsidered = 0;                    // directional lights in the scene
    InlineList<uint32_t, kMaxLights> reservedLights;  // per slot: its Scene::lights index
    uint32_t atlasSize = 0, tiles = 0, split = 0, tileSize = 0;
    double occupancy = 0.0;  // share of the atlas's area its tiles cover
    uint32_t skippedByCascadeBlendCulling = 0;
    uint32_t skippedByReceiverCulling = 0;  // caster/tile pairs whose shadow cannot reach the cascade's receivers
    bool tightFit = false;   // shadows.directional.fit = tight (else the culling spheres)
    InlineList<glm::vec4, kMaxCascades> cullingSpheres;  // per cascade: world centre (xyz), radius (w)
    InlineList<float, kMaxCascades> cascadeSplits;       // per cascade: its far view distance, metres
    InlineList<DirectionalTileStats, kMaxTiles> tileStats;  // tile i = slot * cascades + cascade
    bool trianglesCounted = false;  // the GPU counted the triangles per tile
};

struct OtherShadowStats {
    static constexpr uint32_t kMaxLights = 16, kMaxTiles = 16;  // a spot light takes 1 tile, a point light 6
    static constexpr uint32_t kMaxDroppedLights = 1024;          // every spot/point light a scene may hold
    uint32_t lightsConsidered = 0;                               // spot and point lights in the scene
    InlineList<uint32_t, kMaxLights> reservedLights;             // per slot: its Scene::lights index
    uint32_t lightsDropped = 0;                                  // wanted shadows but did not fit
    InlineList<uint32_t, kMaxDroppedLights> droppedLights;       // their Scene::lights indices (the first 1024)
    uint32_t atlasSize = 0, tiles = 0, split = 0, tileSize = 0, tileBorder = 0;
    double occupancy = 0.0;
    InlineList<ShadowTileDraws, kMaxTiles> tileStats;
    bool trianglesCounted = false;
};

struct ShadowPlanStats {
    DirectionalShadowStats directional;
    OtherShadowStats other;
    uint32_t shadowCasters = 0;  // instances that may cast at all
};

// Caster draws of an atlas: the sum of its tiles' casters.
uint32_t casterDraws(const DirectionalShadowStats& stats);
uint32_t casterDraws(const OtherShadowStats& stats);

// One JSON object {"directional": {...}, "other": {...}, "shadowCasters": n}; docs/cli.md lists its keys.
std::string toJson(const ShadowPlanStats& stats);

}  // namespace penumbra
