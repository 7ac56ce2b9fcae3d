#include "render/shadow_caster_pass.h"

#include "pass_bindings.h"
#include "render/main_pass.h"
#include "render/pass_layouts.h"

namespace penumbra {

ShadowCasterPass::ShadowCasterPass(gpu::Device& device, const GpuScene& gpuScene) : device_(device), scene_(gpuScene) {
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "shadow_caster.vert";
    desc.bindings = shadowCasterBindings();
    desc.pushConstantSize = sizeof(gpu_data::CasterConstants);
    desc.textureTable = gpuScene.textureTable();
    desc.depthFormat = gpu::Format::D32Float;
    desc.depthCompare = gpu::CompareOp::LessOrEqual;  // standard depth in shadow maps: 0 = near the light
    desc.depthClamp = true;
    desc.dynamicDepthBias = true;
    // Both faces cast: thin and open geometry (planes, foliage) must block light from either side.
    desc.cullMode = gpu::CullMode::None;
    desc.debugName = "shadow caster";
    depthOnly_ = device.createGraphicsPipeline(desc);
    desc.fragmentShader = "shadow_caster.frag";
    desc.debugName = "shadow caster alpha-tested";
    alphaTested_ = device.createGraphicsPipeline(desc);
}

ShadowCasterPass::~ShadowCasterPass() {
    device_.destroy(depthOnly_);
    device_.destroy(alphaTested_);
}

void ShadowCasterPass::record(gpu::CommandList& commands, const std::vector<ShadowTile>& tiles,
                              const std::vector<uint32_t>& draw, bool freshAtlas, uint32_t firstCullTile,
                              gpu::TextureHandle atlas, uint32_t atlasSize,
                              const std::vector<gpu::DescriptorWrite>& writes, const ShadowCullingPass& culling,
                              std::string_view passName) {
    if (draw.empty() && !freshAtlas) return;  // every tile cached
    // A fresh atlas is cleared whole; else the drawn tiles are cleared and the cached ones kept.
    std::vector<gpu::ResourceUse>& uses = uses_;
    uses = {freshAtlas ? gpu::discard(atlas, gpu::Usage::DepthTarget) : gpu::use(atlas, gpu::Usage::DepthTarget),
            gpu::use(scene_.indexBuffer(), gpu::Usage::IndexBuffer)};
    scene_.addSceneReads(uses, gpu::Usage::GraphicsRead);
    culling.addDrawUses(uses);
    commands.pass(passName, uses);
    gpu::RenderingDesc rendering;
    rendering.width = rendering.height = atlasSize;
    rendering.depth = {atlas, freshAtlas, 1.0f};
    commands.beginRendering(rendering);
    if (!freshAtlas) {
        std::vector<gpu::Rect>& rects = rects_;
        rects.clear();
        for (uint32_t i : draw) rects.push_back(atlasRect(tiles[i]));
        commands.clearDepthRects(rects, 1.0f);
    }
    std::vector<gpu::DescriptorWrite>& casterWrites = writes_;
    casterWrites.assign(writes.begin(), writes.end());
    // The visible instances of the tile drawn: each tile's draws index the buffer that holds its list.
    casterWrites.push_back({gpu_data::kCasterBindingVisibleInstances, culling.visibleListBuffer(firstCullTile), {}, {}});
    for (uint32_t kind = 0; kind < 2 && !draw.empty(); ++kind) {
        commands.bindPipeline(kind ? alphaTested_ : depthOnly_);
        commands.pushDescriptors(casterWrites);
        commands.bindTextureTable(scene_.textureTable());
        commands.bindIndexBuffer(scene_.indexBuffer());
        gpu::BufferHandle boundList = casterWrites.back().buffer;
        for (uint32_t i : draw) {
            if (const gpu::BufferHandle list = culling.visibleListBuffer(firstCullTile + i); list.id != boundList.id) {
                casterWrites.back().buffer = boundList = list;
                commands.pushDescriptors(casterWrites);
            }
            const ShadowTile& tile = tiles[i];
            const gpu::Rect rect = atlasRect(tile);
            // Other-light tiles keep an empty border: casters are drawn through a smaller scissor, so a
            // filter near the tile's edge never reads a neighbour's depth.
            const uint32_t inset = tile.scissorInset;
            const gpu::Rect scissor{rect.x + int32_t(inset), rect.y + int32_t(inset), rect.width - 2 * inset,
                                    rect.height - 2 * inset};
            commands.setViewport(rect);
            commands.setScissor(scissor);
            commands.setDepthBias(0.0f, tile.slopeScaleBias);
            const gpu_data::CasterConstants constants{tile.clipFromWorld};
            commands.pushConstants(&constants, sizeof(constants));
            const ShadowCullingPass::DrawList draws = culling.drawList(firstCullTile + i, kind);
            commands.drawIndexedIndirectCount(draws.commands, draws.offset, draws.count, draws.countOffset, draws.maxDraws);
        }
    }
    commands.endRendering();
}

}  // namespace penumbra
