#include "shadows/atlas_layout.h"

#include "core/error.h"

namespace penumbra {

AtlasLayout makeAtlasLayout(uint32_t atlasSize, uint32_t tileCount) {
    PENUMBRA_ASSERT(tileCount <= 16);
    AtlasLayout layout;
    layout.atlasSize = atlasSize;
    layout.tileCount = tileCount;
    layout.split = tileCount <= 1 ? 1u : tileCount <= 4 ? 2u : 4u;
    layout.tileSize = atlasSize / layout.split;
    return layout;
}

AtlasTileRect tileRect(const AtlasLayout& layout, uint32_t tileIndex) {
    AtlasTileRect rect;
    rect.offset = glm::uvec2(tileIndex % layout.split, tileIndex / layout.split) * layout.tileSize;
    rect.size = layout.tileSize;
    return rect;
}

glm::mat4 atlasFromClip(const AtlasLayout& layout, uint32_t tileIndex) {
    const float scale = 1.0f / float(layout.split);
    const glm::vec2 tile(float(tileIndex % layout.split), float(tileIndex / layout.split));
    glm::mat4 m(1.0f);
    m[0][0] = 0.5f * scale;
    m[1][1] = 0.5f * scale;
    m[3][0] = (0.5f + tile.x) * scale;
    m[3][1] = (0.5f + tile.y) * scale;
    return m;
}

}  // namespace penumbra
