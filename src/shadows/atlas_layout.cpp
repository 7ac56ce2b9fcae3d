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
    const AtlasTileRect rect = tileRect(layout, tileIndex);
    const float atlas = float(layout.atlasSize);
    // tileSize / atlasSize rather than the tutorial's 1 / split: equal for the power-of-two splits of the
    // directional atlas, and exact on the texels drawn when split 3 leaves a few unused (spot atlas).
    const float scale = float(rect.size) / atlas;
    // Column-major m[column][row]. u = (x / w) * 0.5 * scale + offset, so the homogeneous u is
    // 0.5 * scale * x + offset * w: the offset sits in the column that multiplies the clip w, which
    // serves orthographic tiles (w = 1) and perspective ones (divide by w after this matrix) alike.
    const glm::vec2 offset = glm::vec2(rect.offset) / atlas + 0.5f * scale;
    glm::mat4 m(1.0f);
    m[0][0] = 0.5f * scale;
    m[1][1] = 0.5f * scale;
    m[3][0] = offset.x;
    m[3][1] = offset.y;
    return m;
}

}  // namespace penumbra
