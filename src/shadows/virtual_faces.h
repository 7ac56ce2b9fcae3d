#pragma once
// Geometry of the virtual shadow maps of spot and point lights: every shadowed face (a spot light's one,
// a point light's six) is a square perspective shadow map of `resolution` virtual texels a side with a
// chain of mips, each mip cut into pages of pageSize texels: mip m has (resolution / pageSize) >> m pages
// a side and covers the whole face, the last mip one page. Each visible receiver reads the mip whose
// texels match its footprint on the face (Unreal Engine's "Virtual Shadow Maps" documentation: local
// lights get a 16K virtual map with mips picked by the pixel's footprint).
//
// All the faces share one page table of fixed windows (shadows/virtual_page_pool.h
// VirtualPageTableLayout): level = mip * faceCount + face, pagesPerSide = resolution / pageSize, slot =
// page, the mips as its buckets so that when the pool runs out every face's coarse mips are kept first.
//
// Conventions are the spot atlas's (shadows/spot_projection.h): light view looks along -Z, Vulkan clip
// space (y down), standard depth 0 at the near plane and 1 at the far plane. Page (px, py) of mip m
// covers NDC x in [-1 + 2 px / n, -1 + 2 (px + 1) / n] (n = pages a side of mip m), y likewise, and its
// texel rows go with NDC y, as the rasterizer's viewport lays them out.
//
// Pure functions, no GPU: the marking pass, the page drawing and the lookup follow these rules and
// their tests compare with them.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/image.h"
#include "shadows/virtual_clipmap.h"
#include "shadows/virtual_page_pool.h"

namespace penumbra {

struct VirtualFaceConfig {
    uint32_t resolution = 16384;  // virtual texels along mip 0's side
    uint32_t pageSize = 128;      // texels along a page's side; resolution / pageSize a power of two
};

// Pages along mip 0's side (resolution / pageSize) and the mips down to one page.
uint32_t virtualFacePagesPerSide(const VirtualFaceConfig& config);
uint32_t virtualFaceMipCount(const VirtualFaceConfig& config);
// The page table of faceCount faces: levels mip * faceCount + face, the mips as buckets.
VirtualPageTableLayout virtualFaceTableLayout(const VirtualFaceConfig& config, uint32_t faceCount);
inline uint32_t virtualFaceLevel(uint32_t mip, uint32_t face, uint32_t faceCount) { return mip * faceCount + face; }

// One face as its pages are drawn and read.
struct VirtualFace {
    glm::mat4 clipFromWorld{1.0f};  // perspective, Vulkan clip (y down), standard depth
    glm::vec3 wsPosition{0.0f};     // the light
    float tanHalfFov = 1.0f;        // of the frustum (the cone plus the filter's margin)
};

// The face of a light at wsPosition looking along wsDirection whose cone has half-angle tangent
// coneTangent (1 for a point light's face): the frustum widened so that a filter reaching marginTexels
// of the coarsest mip (one page) around a receiver inside the cone reads texels of this face
// (shadows/spot_projection.h tanHalfFovWithMargin with the page as the tile).
VirtualFace makeVirtualFace(const VirtualFaceConfig& config, const glm::vec3& wsPosition, const glm::vec3& wsDirection,
                            float coneTangent, float nearDistance, float farDistance, float marginTexels);

// The projection of page `page` of mip `mip` of a face (what virtual_face_tiles.comp computes): the face's
// clipFromWorld with the page's NDC square cropped to [-1, 1] (depth and w unchanged).
glm::mat4 virtualFacePageClipFromWorld(const VirtualFace& face, uint32_t pagesPerSide, uint32_t mip, const glm::ivec2& page);

// Where a world point lands on a face: NDC x, y in [-1, 1], depth in [0, 1] and its distance along the
// face's axis; nullopt when it lies behind the light or outside the frustum.
struct FacePoint {
    glm::vec2 ndc{0.0f};
    float depth = 0.0f;
    float lightDistance = 0.0f;
};
std::optional<FacePoint> projectOntoFace(const VirtualFace& face, const glm::vec3& wsPosition);

// The finest mip whose texels are no smaller than a receiver's footprint on the face: wsFootprint
// metres at lightDistance from the light span wsFootprint / (lightDistance * tanHalfFov) NDC units,
// mip m's texel 2^(m + 1) / resolution; clamped to the mips there are.
uint32_t faceMipForFootprint(const VirtualFaceConfig& config, float tanHalfFov, float lightDistance, float wsFootprint);

// The pages of mip `mip` that a filter reaching marginTexels (texels of that mip) around NDC point ndc
// reads, clamped to the mip's pages.
PageRect facePages(const VirtualFaceConfig& config, uint32_t mip, const glm::vec2& ndc, float marginTexels);

// The pages of face `face` (of faceCount) that a caster with world bounds wsBounds covers in every mip:
// its shadow can only change depth there, so when it moves, appears or disappears these pages of its old
// and new bounds are drawn again. The bounds' corners projected onto the face, their NDC rectangle clamped
// to the face; every page of every mip when the bounds reach behind the light's plane (their projection
// is unbounded). Writes one rectangle per mip they touch (level = mip * faceCount + face) into out[0 ..
// mipCount) and returns how many: none when the bounds miss the face's frustum.
uint32_t casterFacePageRects(const VirtualFaceConfig& config, const VirtualFace& face, uint32_t faceIndex,
                             uint32_t faceCount, const Aabb& wsBounds, LevelPageRect* out);

// A light's faces among the table's: a spot light's one, or a point light's six in the cube-map order of
// shadows/spot_projection.h, of which a receiver reads the face of the major axis from the light
// (pointLightFaceOf).
struct VirtualFaceLight {
    uint32_t firstFace = 0;
    bool point = false;  // six faces from firstFace, else one
};

// The request bits of every face's pages that the main view needs this frame (the GPU marking pass's CPU
// reference): per pixel with geometry (reversed-Z depth, 0 = nothing drawn) and per light whose face
// holds it, the pages of its footprint's mip (footprint x footprintScale, shadows.virtual.lodBias) with
// the filter's reach, and of the mip kVirtualPageFallbackLevels coarser. Bits as the GPU writes them
// (virtualPageBit of the table's level and page).
std::vector<uint32_t> markVirtualFacePages(const VirtualFaceConfig& config, std::span<const VirtualFace> faces,
                                           std::span<const VirtualFaceLight> lights, const CameraView& view,
                                           const Image& depth, float marginTexels, float footprintScale);

}  // namespace penumbra
