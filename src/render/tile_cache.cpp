#include "render/tile_cache.h"

namespace penumbra {

namespace {

void append(TileSignature& signature, const glm::vec4& v) {
    for (int i = 0; i < 4; ++i) signature.push_back(v[i]);
}

void append(TileSignature& signature, const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) signature.push_back(m[c][r]);
}

TileSignature baseSignature(const ShadowTile& tile) {
    TileSignature signature;  // the largest fills it: kCapacity counts what is pushed here and below
    append(signature, tile.clipFromWorld);
    signature.push_back(float(tile.rect.offset.x));
    signature.push_back(float(tile.rect.offset.y));
    signature.push_back(float(tile.rect.size));
    signature.push_back(float(tile.scissorInset));
    signature.push_back(tile.slopeScaleBias);
    return signature;
}

}  // namespace

TileSignature directionalTileSignature(const ShadowTile& tile, const DirectionalShadowPlan& plan) {
    TileSignature signature = baseSignature(tile);
    for (const CascadeSphere& sphere : plan.cascades) {
        signature.push_back(sphere.wsCenter.x);
        signature.push_back(sphere.wsCenter.y);
        signature.push_back(sphere.wsCenter.z);
        signature.push_back(sphere.radius);
    }
    signature.push_back(plan.blendCullingFactor);
    // Receiver culling follows the camera: a tile whose square stays while the view turns has other casters.
    const ReceiverVolume& receivers = tile.receiverVolume;
    for (const glm::vec4& plane : receivers.wsSidePlanes) append(signature, plane);
    append(signature, receivers.wsDepthPlane);
    append(signature, glm::vec4(receivers.vsDepthRange, tile.wsReceiverReach, receivers.valid ? 1.0f : 0.0f));
    append(signature, receivers.wsSphere);
    for (int i = 0; i < 3; ++i) {
        signature.push_back(plan.wsReceiverBounds.min[i]);
        signature.push_back(plan.wsReceiverBounds.max[i]);
    }
    return signature;
}

TileSignature otherTileSignature(const ShadowTile& tile) { return baseSignature(tile); }

void TileCache::tilesToDraw(const std::vector<TileSignature>& tiles, uint64_t atlasGeneration, bool compute,
                            uint64_t sceneVersion, bool enabled, std::vector<uint32_t>& draw) {
    const bool keepNothing = !enabled || atlasGeneration != atlasGeneration_ || compute != compute_ ||
                             sceneVersion != sceneVersion_;
    draw.clear();
    for (uint32_t i = 0; i < tiles.size(); ++i)
        if (keepNothing || i >= last_.size() || tiles[i] != last_[i]) draw.push_back(i);
    reused_ = uint32_t(tiles.size() - draw.size());
    last_ = tiles;
    atlasGeneration_ = atlasGeneration;
    sceneVersion_ = sceneVersion;
    compute_ = compute;
}

}  // namespace penumbra
