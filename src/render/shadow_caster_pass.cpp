#include "render/shadow_caster_pass.h"

#include "render/main_pass.h"

namespace penumbra {

ShadowCasterPass::ShadowCasterPass(gpu::Device& device, const GpuScene& gpuScene, const Scene& scene)
    : device_(device), scene_(gpuScene), drawsOfInstance_(scene.instances.size()) {
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "shadow_caster.vert";
    desc.bindings = sceneBindings();
    desc.pushConstantSize = sizeof(glm::mat4);
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
    for (const DrawItem& item : gpuScene.draws()) drawsOfInstance_[item.instanceIndex].push_back(&item);
}

ShadowCasterPass::~ShadowCasterPass() {
    device_.destroy(depthOnly_);
    device_.destroy(alphaTested_);
}

AtlasDrawStats ShadowCasterPass::record(gpu::CommandList& commands, const Scene& scene,
                                        const std::vector<ShadowTile>& tiles, gpu::TextureHandle atlas,
                                        uint32_t atlasSize, const std::vector<gpu::DescriptorWrite>& writes,
                                        const std::string& passName) {
    AtlasDrawStats stats;
    stats.pass = passName;
    stats.tiles = uint32_t(tiles.size());
    commands.transition(atlas, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    gpu::RenderingDesc rendering;
    rendering.width = rendering.height = atlasSize;
    rendering.depth = {atlas, true, 1.0f};
    commands.beginRendering(rendering);
    for (const ShadowTile& tile : tiles) {
        const gpu::Rect rect{int32_t(tile.rect.offset.x), int32_t(tile.rect.offset.y), tile.rect.size, tile.rect.size};
        // Other-light tiles keep an empty border: casters are drawn through a smaller scissor (seed 001 §5.5).
        const uint32_t inset = tile.scissorInset;
        const gpu::Rect scissor{rect.x + int32_t(inset), rect.y + int32_t(inset), rect.width - 2 * inset,
                                rect.height - 2 * inset};
        for (int alphaPass = 0; alphaPass < 2; ++alphaPass) {
            bool bound = false;
            for (uint32_t instanceIndex : tile.casterInstances) {
                for (const DrawItem* item : drawsOfInstance_[instanceIndex]) {
                    const MaterialShadowMode mode = scene.materials.at(item->materialIndex).shadows;
                    if (mode == MaterialShadowMode::Off) continue;
                    if ((mode != MaterialShadowMode::On) != bool(alphaPass)) continue;
                    if (!bound) {
                        commands.bindPipeline(alphaPass ? alphaTested_ : depthOnly_);
                        commands.pushDescriptors(writes);
                        commands.bindTextureTable(scene_.textureTable());
                        commands.bindIndexBuffer(scene_.indexBuffer());
                        commands.setViewport(rect);
                        commands.setScissor(scissor);
                        commands.setDepthBias(0.0f, tile.slopeScaleBias);
                        commands.pushConstants(&tile.clipFromWorld, sizeof(glm::mat4));
                        bound = true;
                    }
                    commands.drawIndexed(item->indexCount, 1, item->firstIndex, item->vertexOffset, item->instanceIndex);
                    ++stats.draws;
                    stats.triangles += item->indexCount / 3;
                }
            }
        }
    }
    commands.endRendering();
    commands.transition(atlas, gpu::TextureState::DepthTarget, gpu::TextureState::ShaderRead);
    return stats;
}

}  // namespace penumbra
