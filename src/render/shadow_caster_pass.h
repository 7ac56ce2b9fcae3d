#pragma once
// Renders the shadow tiles of a plan into a D32 depth target laid out as the atlas (the renderer copies
// the drawn rects into the sampled R32F atlas, AtlasCopyPass): one viewport + scissor per tile, the light's
// slope-scale bias as dynamic depth-bias state, depth clamp for pancaking, and per tile two indirect draw
// lists (opaque, alpha-tested) that the GPU culling pass wrote (after Catlike Coding "Directional Shadows":
// Rendering Shadows, Configurable Biases, Shadow Pancaking, Transparency).
#include <string>
#include <string_view>
#include <vector>

#include "gpu/device.h"
#include "penumbra/renderer.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// A tile's square in its atlas, as a viewport, clear or copy rect.
inline gpu::Rect atlasRect(const ShadowTile& tile) {
    return {int32_t(tile.rect.offset.x), int32_t(tile.rect.offset.y), tile.rect.size, tile.rect.size};
}

class ShadowCasterPass {
public:
    ShadowCasterPass(gpu::Device& device, const GpuScene& gpuScene);
    ~ShadowCasterPass();
    ShadowCasterPass(const ShadowCasterPass&) = delete;
    ShadowCasterPass& operator=(const ShadowCasterPass&) = delete;

    // Clears `atlas` (that D32 target; depth 1 = far, nothing cast) and draws every tile, tile i from the culling pass's
    // lists of culling tile firstCullTile + i, as the frame graph pass `passName`. `writes`: the scene
    // bindings 0-4.
    // Only the tiles `draw` lists (indices into `tiles`) are drawn; with freshAtlas false the others
    // keep their depth (cached tiles: only the drawn tiles are cleared).
    void record(gpu::CommandList& commands, const std::vector<ShadowTile>& tiles, const std::vector<uint32_t>& draw,
                bool freshAtlas, uint32_t firstCullTile, gpu::TextureHandle atlas, uint32_t atlasSize,
                const std::vector<gpu::DescriptorWrite>& writes, const ShadowCullingPass& culling,
                std::string_view passName);

private:
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle depthOnly_;    // shadows "on"
    gpu::PipelineHandle alphaTested_;  // shadows "clip" and "dither"
    // Per-record lists, kept to reuse their storage (a steady frame allocates nothing).
    std::vector<gpu::ResourceUse> uses_;
    std::vector<gpu::Rect> rects_;
    std::vector<gpu::DescriptorWrite> writes_;
};

}  // namespace penumbra
