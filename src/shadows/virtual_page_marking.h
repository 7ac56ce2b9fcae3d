#pragma once
// Which pages of a directional light's virtual shadow map (shadows/virtual_clipmap.h) the main view
// needs this frame, from its depth buffer: the CPU reference of the GPU marking pass
// (render/virtual_page_mark_pass.h, shaders/virtual_page_mark.comp.glsl), which must agree with it.
//
// Per pixel with geometry: its world position, its world footprint, the level it samples
// (levelForReceiver: the finest whose texels are no smaller than the pixel, or a coarser one whose
// window holds it) and every page a filter of marginTexels around it reads (receiverPages). This is
// the page marking of the published virtual shadow maps: Unreal Engine's documentation ("Virtual
// Shadow Maps": each visible pixel marks the clipmap page it samples) and Timberdoodle's (GPU Zen 3,
// "Virtual Shadow Maps": a pass over the depth buffer sets one bit per page-table entry).
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/image.h"
#include "shadows/virtual_clipmap.h"

namespace penumbra {

// The requested pages of every level: one bit per page-table slot, in the layout the GPU pass writes
// (shaders/shared/virtual_page_structs.h: level after level, then slot y * pagesPerSide + x, 32 bits a
// word), and the count of requested pages per level.
struct VirtualPageRequests {
    uint32_t levelCount = 0;
    uint32_t pagesPerSide = 0;
    std::vector<uint32_t> words;
    std::vector<uint32_t> levelPageCounts;  // levelCount entries

    // No page requested, sized for `config`.
    explicit VirtualPageRequests(const VirtualClipmapConfig& config);
    // The bits as the GPU wrote them (virtualPageRequestWords(config) words); counts them per level.
    VirtualPageRequests(const VirtualClipmapConfig& config, std::span<const uint32_t> words);

    bool requested(uint32_t level, const glm::uvec2& slot) const;
    void request(uint32_t level, const glm::uvec2& slot);  // counts the page once
    uint32_t pageCount() const;                              // every level's
};

// Words of the request bits: ceil(levelCount * pagesPerSide^2 / 32).
uint32_t virtualPageRequestWords(const VirtualClipmapConfig& config);

// A pixel's world footprint at view depth vsDepth: the side, in metres, of the square a pixel covers
// on a plane facing the camera at that depth, 2 * vsDepth * tan(yfov / 2) / height (the camera is a
// perspective one; pixels are square). wsFootprintPerDepth is that at one metre.
float wsFootprintPerDepth(const CameraView& view);
float wsPixelFootprint(const CameraView& view, float vsDepth);

// The light-space point the clipmap's levels are centred on: the camera's (lightRotation *
// wsPosition).xy, the lsCamera of placeClipmapLevel.
glm::vec2 lsClipmapCentre(const glm::mat4& lightRotation, const CameraView& view);

// depth: the main view's reversed-Z depth (view.width x view.height, 4 bytes of float per pixel, 0 =
// nothing drawn), as visibleSurfacesFromDepth reads it. lightRotation: clipmapRotationFromWorld of the
// light. marginTexels: the filter's reach around a receiver in texels of the level it samples.
VirtualPageRequests markVirtualPages(const VirtualClipmapConfig& config, const glm::mat4& lightRotation,
                                     const CameraView& view, const Image& depth, float marginTexels);

}  // namespace penumbra
