#include "shadows/virtual_shadow_lookup.h"

#include <cmath>

#include "core/error.h"
#include "shadows/virtual_page_depth.h"
#include "shadows/spot_projection.h"

namespace penumbra {

namespace {

using gpu_data::VirtualPageEntry;
using gpu_data::VirtualShadowLookupData;

constexpr float kMaxTexel = 1073741824.0f;  // texel coordinates beyond this are in no window

int floorDiv(int a, int b) { return a >= 0 ? a / b : -int((uint32_t(-a) + uint32_t(b) - 1u) / uint32_t(b)); }

VirtualClipmapConfig clipmapOf(const VirtualShadowLookupData& data) {
    VirtualClipmapConfig config;
    config.resolution = data.resolution;
    config.pageSize = data.pageSize;
    config.levelCount = data.levelCount;
    config.firstLevelSize = data.firstLevelSize;
    return config;
}

// The entry of page `page` of `level` when it is ready to sample (resident, drawn, its slot holds that
// very page), else null.
const VirtualPageEntry* readyEntry(const VirtualShadowLookupData& data, const VirtualShadowPages& pages, uint32_t level,
                                   const glm::ivec2& page) {
    const int32_t index = virtualShadowEntryIndex(data, level, page);
    if (index < 0) return nullptr;
    const size_t record = size_t(data.firstEntry) + size_t(index);  // of the whole entry buffer
    if (record >= pages.entries.size()) return nullptr;
    const VirtualPageEntry& entry = pages.entries[record];
    const uint32_t state = entry.flags & (gpu_data::kVirtualPageResident | gpu_data::kVirtualPageDirty);
    const bool ready = state == gpu_data::kVirtualPageResident && entry.pageX == page.x && entry.pageY == page.y &&
                       entry.physicalPage < data.poolPagesPerSide * data.poolPagesPerSide;
    return ready ? &entry : nullptr;
}

// The stored depth of virtual texel `texel` of `level`, from the first ready level at or above it that
// holds the texel's centre (texel >> k: each level halves the texels; C++20's >> floors negatives too).
bool texelDepth(const VirtualShadowLookupData& data, const VirtualShadowPages& pages, uint32_t level,
                const glm::ivec2& texel, float& depth) {
    const uint32_t stride = data.faceCount > 0 ? data.faceCount : 1u;  // the next coarser level (mip)
    for (uint32_t coarser = level; coarser < data.levelCount; coarser += stride) {
        const int shift = int((coarser - level) / stride);
        const glm::ivec2 t(texel.x >> shift, texel.y >> shift);
        const glm::ivec2 page = virtualShadowPageOfTexel(data, t);
        const VirtualPageEntry* entry = readyEntry(data, pages, coarser, page);
        if (!entry) continue;
        const int physical = int(entry->physicalPage), pool = int(data.poolPagesPerSide), size = int(data.pageSize);
        const glm::ivec2 origin = glm::ivec2(physical % pool, physical / pool) * size + glm::ivec2(0, int(data.poolOriginY));
        const glm::ivec2 poolTexel = origin + t - page * size;  // pool texture texels
        depth = virtualPoolDepth(pages.poolCodes, uint32_t(pool * size), uint32_t(poolTexel.x), uint32_t(poolTexel.y),
                                 {entry->depthMin, entry->depthStep});
        return true;
    }
    return false;
}

float texelLit(const VirtualShadowLookupData& data, const VirtualShadowPages& pages, uint32_t level, const glm::ivec2& texel,
               float depth) {
    float stored = 0.0f;
    if (!texelDepth(data, pages, level, texel, stored)) return 1.0f;
    return depth <= stored ? 1.0f : 0.0f;
}

float mixFloat(float a, float b, float t) { return a * (1.0f - t) + b * t; }  // GLSL mix

// The bilinear-weighted compare of the 2 x 2 texels of `level` around t (texel units, centres at i + 0.5).
float bilinearLit(const VirtualShadowLookupData& data, const VirtualShadowPages& pages, uint32_t level, const glm::vec2& t,
                  float depth) {
    const glm::vec2 corner = glm::floor(t - 0.5f);  // texel (i, j) of the 2 x 2 block
    const glm::vec2 f = t - 0.5f - corner;
    const glm::ivec2 c(corner);
    const float lit00 = texelLit(data, pages, level, c, depth);
    const float lit10 = texelLit(data, pages, level, c + glm::ivec2(1, 0), depth);
    const float lit01 = texelLit(data, pages, level, c + glm::ivec2(0, 1), depth);
    const float lit11 = texelLit(data, pages, level, c + glm::ivec2(1, 1), depth);
    return mixFloat(mixFloat(lit00, lit10, f.x), mixFloat(lit01, lit11, f.x), f.y);
}

}  // namespace

gpu_data::VirtualShadowLookupData packVirtualShadowLookup(const VirtualClipmapConfig& config,
                                                          const glm::mat4& lightRotationFromWorld, float lsDepthNear,
                                                          float lsDepthFar, const glm::vec2& lsCamera,
                                                          uint32_t poolPagesPerSide, uint32_t poolOriginY,
                                                          uint32_t firstEntry) {
    PENUMBRA_ASSERT(config.levelCount <= gpu_data::kVirtualPageMaxLevels && lsDepthNear != lsDepthFar);
    VirtualShadowLookupData data{};
    data.lightRotationFromWorld = lightRotationFromWorld;
    data.lsDepthNear = lsDepthNear;
    data.depthPerMetre = 1.0f / (lsDepthNear - lsDepthFar);
    data.firstLevelSize = config.firstLevelSize;
    data.resolution = config.resolution;
    data.pagesPerSide = pagesPerSide(config);
    data.pageSize = config.pageSize;
    data.levelCount = config.levelCount;
    data.poolPagesPerSide = poolPagesPerSide;
    data.texelsPerMetre = float(config.resolution) / config.firstLevelSize;
    data.poolOriginY = poolOriginY;
    data.firstEntry = firstEntry;
    packClipmapWindows(config, lsCamera, data.levels);
    return data;
}

int32_t virtualShadowEntryIndex(const VirtualShadowLookupData& data, uint32_t level, const glm::ivec2& page) {
    const int n = int(data.pagesPerSide);
    if (data.faceCount > 0) {  // fixed windows: slot = page
        if (page.x < 0 || page.y < 0 || page.x >= n || page.y >= n) return -1;
        return int32_t((level * data.pagesPerSide + uint32_t(page.y)) * data.pagesPerSide + uint32_t(page.x));
    }
    const gpu_data::VirtualPageLevelWindow& window = data.levels[level];
    const glm::ivec2 offset = page - glm::ivec2(window.minPageX, window.minPageY);
    if (offset.x < 0 || offset.y < 0 || offset.x >= n || offset.y >= n) return -1;
    const glm::uvec2 slot = (glm::uvec2(offset) + glm::uvec2(window.minSlotX, window.minSlotY)) % data.pagesPerSide;
    return int32_t((level * data.pagesPerSide + slot.y) * data.pagesPerSide + slot.x);
}

int32_t virtualShadowReadyPage(const VirtualShadowLookupData& data, const VirtualShadowPages& pages, uint32_t level,
                               const glm::ivec2& page) {
    const VirtualPageEntry* entry = readyEntry(data, pages, level, page);
    return entry ? int32_t(entry->physicalPage) : -1;
}

glm::ivec2 virtualShadowPageOfTexel(const VirtualShadowLookupData& data, const glm::ivec2& texel) {
    const int size = int(data.pageSize);
    return {floorDiv(texel.x, size), floorDiv(texel.y, size)};
}

VirtualShadowSample sampleVirtualShadow(const VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                                        const glm::vec3& wsPosition, float wsFootprint) {
    const glm::vec3 lsPosition(data.lightRotationFromWorld * glm::vec4(wsPosition, 1.0f));
    const float depth = (data.lsDepthNear - lsPosition.z) * data.depthPerMetre;
    const glm::vec2 texel0 = glm::vec2(lsPosition) * data.texelsPerMetre;  // level 0's texel units
    for (uint32_t level = levelForFootprint(clipmapOf(data), wsFootprint); level < data.levelCount; ++level) {
        const glm::vec2 t(std::ldexp(texel0.x, -int(level)), std::ldexp(texel0.y, -int(level)));  // exact
        if (!(std::abs(t.x) <= kMaxTexel && std::abs(t.y) <= kMaxTexel)) continue;
        const glm::ivec2 page = virtualShadowPageOfTexel(data, glm::ivec2(glm::floor(t)));
        if (virtualShadowReadyPage(data, pages, level, page) < 0) continue;
        return {bilinearLit(data, pages, level, t, depth), int32_t(level)};
    }
    return {};
}

gpu_data::VirtualShadowLookupData packVirtualFaceLookup(const VirtualFaceConfig& config, uint32_t faceCount,
                                                        uint32_t poolPagesPerSide) {
    PENUMBRA_ASSERT(faceCount > 0);
    VirtualShadowLookupData data{};
    data.resolution = config.resolution;
    data.pagesPerSide = virtualFacePagesPerSide(config);
    data.pageSize = config.pageSize;
    data.levelCount = virtualFaceMipCount(config) * faceCount;
    data.poolPagesPerSide = poolPagesPerSide;
    data.faceCount = faceCount;
    return data;
}

VirtualShadowSample sampleVirtualFace(const VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                                      std::span<const VirtualFace> faces, const VirtualFaceLight& light,
                                      const glm::vec3& wsPosition, float wsFootprint) {
    PENUMBRA_ASSERT(data.faceCount == faces.size() && light.firstFace < faces.size());
    const uint32_t face =
        light.firstFace + (light.point ? pointLightFaceOf(wsPosition - faces[light.firstFace].wsPosition) : 0u);
    const std::optional<FacePoint> point = projectOntoFace(faces[face], wsPosition);
    if (!point) return {};  // behind the light or outside its face: nothing cast
    const VirtualFaceConfig config{data.resolution, data.pageSize};
    const uint32_t mipCount = data.levelCount / data.faceCount;
    for (uint32_t mip = faceMipForFootprint(config, faces[face].tanHalfFov, point->lightDistance, wsFootprint);
         mip < mipCount; ++mip) {
        const uint32_t level = virtualFaceLevel(mip, face, data.faceCount);
        const glm::vec2 t = (point->ndc * 0.5f + 0.5f) * float(data.resolution >> mip);  // the mip's texels
        const glm::ivec2 page = virtualShadowPageOfTexel(data, glm::ivec2(glm::floor(t)));
        if (virtualShadowReadyPage(data, pages, level, page) < 0) continue;
        return {bilinearLit(data, pages, level, t, point->depth), int32_t(level)};
    }
    return {};
}

}  // namespace penumbra
