#pragma once
// Geometry of a directional light's virtual shadow map: a clipmap of square levels in the light's
// rotation-only space (clipmapRotationFromWorld), each `resolution` virtual texels a side, cut into
// square pages of `pageSize` texels; level i is firstLevelSize * 2^i metres wide. The design follows
// the published virtual shadow maps: Unreal Engine's documentation ("Virtual Shadow Maps": 16K virtual
// texels, 128-texel pages, a clipmap whose radius doubles per level) and Timberdoodle's (GPU Zen 3,
// "Virtual Shadow Maps": wrap-around page tables).
//
// Every level's texel and page grid is fixed in light space: page (x, y) of level i covers
// [x, x + 1) x [y, y + 1) page widths from the light-space origin, whatever the camera does. A level's
// window (the pages it can hold) is the pagesPerSide x pagesPerSide pages centred on the camera,
// snapped to whole pages, so when the camera moves, texels never move relative to the world (no
// shimmer) and only the pages that enter the window are new. A page's slot in the level's page table
// is its coordinate modulo pagesPerSide (wrap-around addressing): a page keeps its slot for as long as
// it stays in the window.
//
// Pure functions, no GPU: the page-marking pass and its tests use the same rules.
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "virtual_page_structs.h"

namespace penumbra {

struct VirtualClipmapConfig {
    uint32_t resolution = 16384;  // virtual texels along a level's side
    uint32_t pageSize = 128;      // texels along a page's side; divides resolution
    uint32_t levelCount = 16;
    float firstLevelSize = 2.0f;  // metres along level 0's side; level i is firstLevelSize * 2^i
};

// The clipmap's light space: lightRotationFromWorld (the cascades' frame, whose y axis is world up seen
// from the light) turned by kClipmapGridTurnDegrees about the light's direction. In the cascades' frame
// every vertical caster (a pole, a wall's edge, a tree trunk) casts a shadow whose sides run along the
// texel columns, so the rasterized edge snaps to a texel border and the filter cannot average the
// staircase away: the edge sits up to half a texel off, the same way all along it. Turned by 45 degrees
// those sides cross the texels diagonally, and the tent filter of a staircase whose steps are one texel
// finds the edge within a small fraction of a texel (a fence of 6 cm poles at 1920x1080: half the
// misclassified pixels and half the shimmer; docs/fidelity.md, "A clipmap grid turned 45 degrees").
constexpr float kClipmapGridTurnDegrees = 45.0f;
glm::mat4 clipmapRotationFromWorld(const glm::vec3& wsLightDirection);

// Pages along a level's side: resolution / pageSize.
uint32_t pagesPerSide(const VirtualClipmapConfig& config);

// A rectangle of pages, min and max inclusive, in a level's global page coordinates.
struct PageRect {
    glm::ivec2 min{0};
    glm::ivec2 max{-1};
    bool empty() const { return max.x < min.x || max.y < min.y; }
    bool contains(const PageRect& other) const;
    uint32_t pageCount() const;
};

// One level placed around the camera.
struct ClipmapLevel {
    uint32_t level = 0;
    float lsSize = 0.0f;       // metres along the side
    float lsTexelSize = 0.0f;  // metres per texel
    float lsPageSize = 0.0f;   // metres per page
    uint32_t pagesPerSide = 0;
    PageRect window;           // the pages the level holds this frame (pagesPerSide a side)
};

// Level `level` around a camera at lsCamera (the camera's light-space x, y): the window is the
// pagesPerSide pages on each axis whose middle page (pagesPerSide / 2 from the window's min) holds
// the camera.
ClipmapLevel placeClipmapLevel(const VirtualClipmapConfig& config, uint32_t level, const glm::vec2& lsCamera);

// The global page holding a light-space point.
glm::ivec2 pageOf(const ClipmapLevel& level, const glm::vec2& lsPosition);

// The page table slot of a global page: its coordinates modulo pagesPerSide, in [0, pagesPerSide).
glm::uvec2 pageTableSlot(const ClipmapLevel& level, const glm::ivec2& page);

// The finest level whose texels are no smaller than a pixel's world footprint (metres): texel(i) <=
// footprint < texel(i + 1), clamped to the levels there are. Finer texels than the pixel buys nothing.
uint32_t levelForFootprint(const VirtualClipmapConfig& config, float wsPixelFootprint);

// The pages a filter reading around lsPosition touches: the texels within marginTexels of it (the PCF
// kernel's or the PCSS search's radius), so a filter never reads a page nobody asked for.
PageRect receiverPages(const ClipmapLevel& level, const glm::vec2& lsPosition, float marginTexels);

// The level a receiver samples: levelForFootprint, or the first coarser one whose window holds all of
// receiverPages (the window is centred on the camera, far receivers need wide levels); none beyond
// the last level (the receiver is outside the clipmap).
std::optional<uint32_t> levelForReceiver(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                                         const glm::vec2& lsReceiver, float wsPixelFootprint, float marginTexels);

// The window's pages that light-space bounds (a caster's, x and y) touch: the pages to draw again
// when that caster moves. Empty when the bounds miss the window.
PageRect pagesTouchedByBounds(const ClipmapLevel& level, const Aabb& lsBounds);

// One level's rectangle of pages.
struct LevelPageRect {
    uint32_t level = 0;
    PageRect pages;
};

// The pages a caster with world bounds wsBounds covers in every level's window, as seen by the light of
// rotation lightRotation (clipmapRotationFromWorld) with the levels around lsCamera: its shadow can only
// change depth there, so when a caster moves, appears or disappears these pages of its old and of its
// new bounds are drawn again. Writes one rectangle per level the bounds touch into out[0 ..
// config.levelCount) and returns how many.
uint32_t casterPageRects(const VirtualClipmapConfig& config, const glm::mat4& lightRotation, const glm::vec2& lsCamera,
                         const Aabb& wsBounds, LevelPageRect* out);

// Every level's window around lsCamera as the GPU reads it (the page table's and the lookup's data):
// its first page and that page's slot, into levels[0 .. config.levelCount).
void packClipmapWindows(const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                        gpu_data::VirtualPageLevelWindow* levels);

}  // namespace penumbra
