#include "shadows/virtual_faces.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.h"
#include "shadows/spot_projection.h"
#include "shadows/virtual_page_marking.h"
#include "shadows/visible_surfaces.h"
#include "virtual_page_structs.h"

namespace penumbra {

uint32_t virtualFacePagesPerSide(const VirtualFaceConfig& config) {
    PENUMBRA_ASSERT(config.pageSize > 0 && config.resolution % config.pageSize == 0 &&
                    std::has_single_bit(config.resolution / config.pageSize));
    return config.resolution / config.pageSize;
}

uint32_t virtualFaceMipCount(const VirtualFaceConfig& config) {
    return uint32_t(std::countr_zero(virtualFacePagesPerSide(config))) + 1;
}

VirtualPageTableLayout virtualFaceTableLayout(const VirtualFaceConfig& config, uint32_t faceCount) {
    PENUMBRA_ASSERT(faceCount > 0);
    return {virtualFacePagesPerSide(config), virtualFaceMipCount(config) * faceCount, faceCount, true};
}

VirtualFace makeVirtualFace(const VirtualFaceConfig& config, const glm::vec3& wsPosition, const glm::vec3& wsDirection,
                            float coneTangent, float nearDistance, float farDistance, float marginTexels) {
    VirtualFace face;
    face.wsPosition = wsPosition;
    face.tanHalfFov = tanHalfFovWithMargin(coneTangent, config.pageSize, marginTexels);
    face.clipFromWorld = perspectiveClipFromLight(face.tanHalfFov, nearDistance, farDistance) *
                         perspectiveLightFromWorld(wsPosition, wsDirection);
    return face;
}

glm::mat4 virtualFacePageClipFromWorld(const VirtualFace& face, uint32_t pagesPerSide, uint32_t mip, const glm::ivec2& page) {
    // Operation for operation as virtual_face_tiles.comp pageTile.
    const float pages = float(pagesPerSide >> mip);  // the page is 2 / pages NDC wide
    glm::mat4 crop(1.0f);
    crop[0][0] = pages;
    crop[1][1] = pages;
    crop[3][0] = pages - 1.0f - 2.0f * float(page.x);
    crop[3][1] = pages - 1.0f - 2.0f * float(page.y);
    return crop * face.clipFromWorld;
}

std::optional<FacePoint> projectOntoFace(const VirtualFace& face, const glm::vec3& wsPosition) {
    const glm::vec4 clip = face.clipFromWorld * glm::vec4(wsPosition, 1.0f);
    if (!(clip.w > 0.0f)) return std::nullopt;  // behind the light
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    if (std::abs(ndc.x) > 1.0f || std::abs(ndc.y) > 1.0f || ndc.z < 0.0f || ndc.z > 1.0f) return std::nullopt;
    return FacePoint{glm::vec2(ndc), ndc.z, clip.w};
}

uint32_t faceMipForFootprint(const VirtualFaceConfig& config, float tanHalfFov, float lightDistance, float wsFootprint) {
    const float ndcFootprint = wsFootprint / (lightDistance * tanHalfFov);
    const float ndcTexel0 = 2.0f / float(config.resolution);
    if (!(ndcFootprint > ndcTexel0)) return 0;
    int exponent = 0;
    std::frexp(ndcFootprint / ndcTexel0, &exponent);  // ratio = m 2^exponent, m in [0.5, 1)
    return uint32_t(std::min(exponent - 1, int(virtualFaceMipCount(config)) - 1));
}

PageRect facePages(const VirtualFaceConfig& config, uint32_t mip, const glm::vec2& ndc, float marginTexels) {
    const int32_t pages = int32_t(virtualFacePagesPerSide(config) >> mip);
    const float texels = float(pages) * float(config.pageSize);  // the mip's side
    const glm::vec2 texel = (ndc * 0.5f + 0.5f) * texels;
    const auto pageOf = [&](const glm::vec2& t) {
        return glm::clamp(glm::ivec2(glm::floor(t / float(config.pageSize))), glm::ivec2(0), glm::ivec2(pages - 1));
    };
    return {pageOf(texel - marginTexels), pageOf(texel + marginTexels)};
}

uint32_t casterFacePageRects(const VirtualFaceConfig& config, const VirtualFace& face, uint32_t faceIndex,
                             uint32_t faceCount, const Aabb& wsBounds, LevelPageRect* out) {
    if (!wsBounds.valid()) return 0;
    glm::vec2 ndcMin(1e30f), ndcMax(-1e30f);
    bool behind = false, allBeyondFar = true;
    for (uint32_t i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? wsBounds.max.x : wsBounds.min.x, (i & 2) ? wsBounds.max.y : wsBounds.min.y,
                               (i & 4) ? wsBounds.max.z : wsBounds.min.z);
        const glm::vec4 clip = face.clipFromWorld * glm::vec4(corner, 1.0f);
        if (!(clip.w > 0.0f)) {
            behind = true;
            continue;
        }
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        ndcMin = glm::min(ndcMin, ndc);
        ndcMax = glm::max(ndcMax, ndc);
        allBeyondFar = allBeyondFar && clip.z > clip.w;
    }
    if (behind) {  // the box reaches behind the light: its projection is unbounded
        ndcMin = glm::vec2(-1.0f);
        ndcMax = glm::vec2(1.0f);
    } else if (allBeyondFar || ndcMax.x < -1.0f || ndcMax.y < -1.0f || ndcMin.x > 1.0f || ndcMin.y > 1.0f) {
        return 0;  // nothing of it in the frustum
    }
    ndcMin = glm::clamp(ndcMin, glm::vec2(-1.0f), glm::vec2(1.0f));
    ndcMax = glm::clamp(ndcMax, glm::vec2(-1.0f), glm::vec2(1.0f));
    const uint32_t mips = virtualFaceMipCount(config);
    for (uint32_t mip = 0; mip < mips; ++mip) {
        const PageRect low = facePages(config, mip, ndcMin, 0.0f), high = facePages(config, mip, ndcMax, 0.0f);
        out[mip] = {virtualFaceLevel(mip, faceIndex, faceCount), PageRect{low.min, high.max}};
    }
    return mips;
}

namespace {

void requestPages(std::vector<uint32_t>& words, const VirtualPageTableLayout& layout, uint32_t level, const PageRect& pages) {
    for (int32_t y = pages.min.y; y <= pages.max.y; ++y)
        for (int32_t x = pages.min.x; x <= pages.max.x; ++x) {
            const uint32_t bit = gpu_data::virtualPageBit(level, layout.pagesPerSide, uint32_t(x), uint32_t(y));
            words[bit / 32] |= 1u << (bit % 32);
        }
}

// The pages one receiver needs from the face of `light` that holds it, if any.
void markReceiver(std::vector<uint32_t>& words, const VirtualFaceConfig& config, const VirtualPageTableLayout& layout,
                  std::span<const VirtualFace> faces, const VirtualFaceLight& light, const glm::vec3& wsPosition,
                  float wsFootprint, float marginTexels) {
    const uint32_t face = light.firstFace + (light.point ? pointLightFaceOf(wsPosition - faces[light.firstFace].wsPosition) : 0u);
    const std::optional<FacePoint> point = projectOntoFace(faces[face], wsPosition);
    if (!point) return;
    const uint32_t mipCount = virtualFaceMipCount(config);
    const uint32_t mip = faceMipForFootprint(config, faces[face].tanHalfFov, point->lightDistance, wsFootprint);
    const uint32_t fallback = std::min(mip + gpu_data::kVirtualPageFallbackLevels, mipCount - 1);
    const uint32_t faceCount = uint32_t(faces.size());
    requestPages(words, layout, virtualFaceLevel(mip, face, faceCount), facePages(config, mip, point->ndc, marginTexels));
    if (fallback != mip)
        requestPages(words, layout, virtualFaceLevel(fallback, face, faceCount),
                     facePages(config, fallback, point->ndc, marginTexels));
}

}  // namespace

std::vector<uint32_t> markVirtualFacePages(const VirtualFaceConfig& config, std::span<const VirtualFace> faces,
                                           std::span<const VirtualFaceLight> lights, const CameraView& view,
                                           const Image& depth, float marginTexels, float footprintScale) {
    PENUMBRA_ASSERT(depth.width == view.width && depth.height == view.height && depth.channels == 4 && !faces.empty());
    const VirtualPageTableLayout layout = virtualFaceTableLayout(config, uint32_t(faces.size()));
    std::vector<uint32_t> words((layout.entryCount() + 31) / 32, 0u);
    forEachSurfacePixel(depth, view, [&](const glm::vec3& wsPosition, float vsDepth) {
        const float wsFootprint = wsPixelFootprint(view, vsDepth) * footprintScale;
        for (const VirtualFaceLight& light : lights)
            markReceiver(words, config, layout, faces, light, wsPosition, wsFootprint, marginTexels);
    });
    return words;
}

}  // namespace penumbra
