#include "shadows/cull_packing.h"

#include <algorithm>
#include <cstddef>

#include "core/error.h"
#include "shadows/spot_culling.h"

namespace penumbra {

namespace {

// What the compute rasterizer needs of every tile: its projection, viewport and scissor, the bias.
void packRaster(gpu_data::CullTile& packed, const ShadowTile& tile) {
    packed.clipFromWorld = tile.clipFromWorld;
    packed.viewport = glm::vec4(float(tile.rect.offset.x), float(tile.rect.offset.y), float(tile.rect.size),
                                float(tile.rect.size));
    const uint32_t inset = tile.scissorInset;
    packed.scissor = glm::uvec4(tile.rect.offset.x + inset, tile.rect.offset.y + inset,
                                tile.rect.offset.x + tile.rect.size - inset, tile.rect.offset.y + tile.rect.size - inset);
    packed.slopeBias = tile.slopeScaleBias;
}

gpu_data::CullTile directionalTile(const ShadowTile& tile, float blendCullingFactor) {
    gpu_data::CullTile packed{};
    packed.lightFromWorld = tile.lightFromWorld;
    packed.kind = gpu_data::kCullTileDirectional;
    packed.halfExtent = tile.lsHalfExtent;
    packed.farDistance = tile.farDistance;
    packed.cascadeIndex = float(tile.cascadeIndex);
    packed.blendCullingFactor = blendCullingFactor;
    // The light travels along -Z of its view: the third row of the rotation, negated (as caster_culling.cpp).
    packed.wsLightDirection = -glm::vec3(tile.lightFromWorld[0][2], tile.lightFromWorld[1][2], tile.lightFromWorld[2][2]);
    const ReceiverVolume& receivers = tile.receiverVolume;
    for (size_t i = 0; i < receivers.wsSidePlanes.size(); ++i) packed.planes[i] = receivers.wsSidePlanes[i];
    packed.planes[4] = receivers.wsDepthPlane;
    packed.receiverDepth = glm::vec4(receivers.vsDepthRange, tile.wsReceiverReach, receivers.valid ? 1.0f : 0.0f);
    packed.receiverSphere = receivers.wsSphere;
    packRaster(packed, tile);
    return packed;
}

gpu_data::CullTile perspectiveTile(const ShadowTile& tile) {
    gpu_data::CullTile packed{};
    const std::array<glm::vec4, 5> planes = clipFrustumPlanes(tile.clipFromWorld);
    for (size_t i = 0; i < planes.size(); ++i) packed.planes[i] = planes[i];
    const Aabb bounds = perspectiveFrustumBounds(tile.clipFromWorld, tile.wsApex);
    packed.frustumMin = bounds.min;
    packed.kind = gpu_data::kCullTilePerspective;
    packed.frustumMax = bounds.max;
    packRaster(packed, tile);
    return packed;
}

}  // namespace

gpu_data::CullFrame packCullFrame(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount) {
    gpu_data::CullFrame packed{};
    const auto& directional = frame.directional;
    const bool receivers = directional.wsReceiverBounds.valid();
    for (size_t i = 0; i < directional.cascades.size() && i < 4; ++i)
        packed.spheres[i] = glm::vec4(directional.cascades[i].wsCenter, directional.cascades[i].radius);
    packed.wsReceiverMin = glm::vec4(receivers ? directional.wsReceiverBounds.min : glm::vec3(0.0f), 0.0f);
    packed.wsReceiverMax = glm::vec4(receivers ? directional.wsReceiverBounds.max : glm::vec3(0.0f), 0.0f);
    packed.instanceCount = instanceCount;
    packed.meshCount = meshCount;
    return packed;
}

size_t CullTileUpload::bytes() const {
    return sizeof(header) + std::max<size_t>(header.count, 1) * sizeof(gpu_data::CullTile);
}

size_t RasterTileUpload::bytes() const { return sizeof(header) + std::max<size_t>(header.count, 1) * sizeof(uint32_t); }

void packCullTiles(const ShadowFrame& frame, uint32_t instanceCount, uint32_t meshCount, CullTileUpload& out) {
    static_assert(offsetof(CullTileUpload, tiles) == sizeof(gpu_data::CullTileListHeader), "the records follow the header");
    const auto& directional = frame.directional;
    const size_t tileCount = directional.tiles.size() + frame.other.tiles.size();
    if (tileCount > gpu_data::kMaxCullTiles)
        throw Error("internal: " + std::to_string(tileCount) + " shadow tiles exceed the culling pass's " +
                    std::to_string(gpu_data::kMaxCullTiles));
    // No receiver: nothing to blend-cull for (as cullTileCasters: factor 0 culls nothing).
    const float blendCullingFactor = directional.wsReceiverBounds.valid() ? directional.blendCullingFactor : 0.0f;
    uint32_t t = 0;
    for (const ShadowTile& tile : directional.tiles) out.tiles[t++] = directionalTile(tile, blendCullingFactor);
    for (const ShadowTile& tile : frame.other.tiles) out.tiles[t++] = perspectiveTile(tile);
    const uint32_t count = uint32_t(tileCount), group = gpu_data::kCullWorkgroupSize;
    out.header = {};
    out.header.cullDispatch = glm::uvec4((instanceCount + group - 1) / group, count, 1, 0);
    out.header.drawsDispatch = glm::uvec4((meshCount + group - 1) / group, count, 1, 0);
    out.header.count = count;
}

glm::uvec4 rasterExpandDispatch(uint32_t instanceCount, uint32_t tiles) {
    const uint32_t group = gpu_data::kRasterExpandGroup;
    return glm::uvec4(std::max((instanceCount + group - 1) / group, 1u), 1, tiles, 0);
}

void packRasterTiles(const std::vector<ShadowTile>& tiles, std::span<const uint32_t> drawn, uint32_t firstCullTile,
                     uint32_t instanceCount, RasterTileUpload& out) {
    PENUMBRA_ASSERT(drawn.size() <= gpu_data::kMaxCullTiles);
    static_assert(offsetof(RasterTileUpload, entries) == sizeof(gpu_data::RasterTileListHeader), "the entries follow the header");
    uint32_t largest = 0, count = 0;
    for (uint32_t i : drawn) {
        if (count == gpu_data::kMaxCullTiles) break;
        out.entries[count++] = firstCullTile + i;
        largest = std::max(largest, tiles[i].rect.size);
    }
    const uint32_t groups = (largest + gpu_data::kRasterClearGroup - 1) / gpu_data::kRasterClearGroup;
    out.header = {};
    out.header.clearDispatch = glm::uvec4(groups, groups, count, 0);
    out.header.expandDispatch = rasterExpandDispatch(instanceCount, count);
    out.header.count = count;
}

DepthPyramidLayout depthPyramidLayout(uint32_t width, uint32_t height) {
    PENUMBRA_ASSERT(width > 0 && height > 0);
    DepthPyramidLayout layout;
    glm::uvec2 size((width + 1) / 2, (height + 1) / 2);
    while (true) {
        layout.sizes.push_back(size);
        layout.offsets.push_back(layout.texels);
        layout.texels += size.x * size.y;
        if (size == glm::uvec2(1)) break;
        size = (size + 1u) / 2u;
    }
    return layout;
}

uint32_t depthPyramidLevelCount(uint32_t width, uint32_t height) {
    PENUMBRA_ASSERT(width > 0 && height > 0);
    uint32_t levels = 1;
    for (glm::uvec2 size((width + 1) / 2, (height + 1) / 2); size != glm::uvec2(1); size = (size + 1u) / 2u) ++levels;
    return levels;
}

gpu_data::CullCamera packCullCamera(const glm::mat4& clipFromWorld, uint32_t width, uint32_t height, ViewCulling culling) {
    const uint32_t mode = culling == ViewCulling::Occlusion ? gpu_data::kViewCullingOcclusion
                          : culling == ViewCulling::Frustum ? gpu_data::kViewCullingFrustum
                                                            : gpu_data::kViewCullingNone;
    const uint32_t levels = depthPyramidLevelCount(width, height);
    if (levels > gpu_data::kMaxPyramidLevels)
        throw Error("internal: a " + std::to_string(width) + "x" + std::to_string(height) + " view needs " +
                    std::to_string(levels) + " depth pyramid levels (at most " +
                    std::to_string(gpu_data::kMaxPyramidLevels) + ")");
    gpu_data::CullCamera camera{};
    camera.clipFromWorld = clipFromWorld;
    camera.width = width;
    camera.height = height;
    camera.pyramidLevels = levels;
    camera.culling = mode;
    camera.pyramidWidth = (width + 1) / 2;  // level 0
    camera.pyramidHeight = (height + 1) / 2;
    return camera;
}

}  // namespace penumbra
