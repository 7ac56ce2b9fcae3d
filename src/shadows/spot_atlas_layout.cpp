#include "shadows/spot_atlas_layout.h"

#include "core/error.h"

namespace penumbra {

SpotAtlasLayout makeSpotAtlasLayout(uint32_t atlasSize, uint32_t tileCount) {
    PENUMBRA_ASSERT(tileCount <= kMaxOtherShadowTiles);
    SpotAtlasLayout layout;
    layout.atlasSize = atlasSize;
    layout.tileCount = tileCount;
    layout.split = tileCount <= 1 ? 1u : tileCount <= 4 ? 2u : tileCount <= 9 ? 3u : 4u;
    layout.tileSize = atlasSize / layout.split;
    layout.border = layout.split > 1 ? kOtherTileBorder : 0u;  // one tile: no border
    return layout;
}

AtlasTileRect spotTileViewport(const SpotAtlasLayout& layout, uint32_t tileIndex) {
    return tileRect(layout.asAtlasLayout(), tileIndex);
}

AtlasTileRect spotTileScissor(const SpotAtlasLayout& layout, uint32_t tileIndex) {
    AtlasTileRect rect = spotTileViewport(layout, tileIndex);
    rect.offset += glm::uvec2(layout.border);
    rect.size -= 2 * layout.border;
    return rect;
}

glm::mat4 spotAtlasFromClip(const SpotAtlasLayout& layout, uint32_t tileIndex) {
    return atlasFromClip(layout.asAtlasLayout(), tileIndex);  // divide by w afterwards
}

glm::vec4 spotTileSampleBounds(const SpotAtlasLayout& layout, uint32_t tileIndex, float reachTexels) {
    const AtlasTileRect scissor = spotTileScissor(layout, tileIndex);
    const float atlas = float(layout.atlasSize);
    const glm::vec2 min = (glm::vec2(scissor.offset) + reachTexels) / atlas;
    const glm::vec2 max = (glm::vec2(scissor.offset) + float(scissor.size) - reachTexels) / atlas;
    return glm::vec4(min, max);
}

}  // namespace penumbra
