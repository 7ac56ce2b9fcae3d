#include "render/main_pass.h"

#include <algorithm>

namespace penumbra {

std::vector<gpu::BindingDesc> sceneBindings() {
    using gpu::DescriptorType;
    return {{0, DescriptorType::UniformBuffer}, {1, DescriptorType::StorageBuffer}, {2, DescriptorType::StorageBuffer},
            {3, DescriptorType::StorageBuffer}, {4, DescriptorType::StorageBuffer}};
}

std::vector<gpu::DescriptorWrite> sceneDescriptorWrites(const GpuScene& gpuScene, gpu::BufferHandle frame,
                                                        gpu::BufferHandle lights) {
    return {{0, frame, {}, {}}, {1, gpuScene.vertexBuffer(), {}, {}}, {2, gpuScene.instanceBuffer(), {}, {}},
            {3, gpuScene.materialBuffer(), {}, {}}, {4, lights, {}, {}}};
}

const MainPass::PipelineSet& MainPass::pipelines(const Target& target, const MainPassInputs& inputs) {
    std::vector<std::pair<uint32_t, uint32_t>> constants;
    for (const gpu::SpecConstant& c : target.specialization) constants.emplace_back(c.id, c.value);
    const PipelineKey key{target.colorFormat, target.fragmentShader, constants};
    auto found = pipelineSets_.find(key);
    if (found != pipelineSets_.end()) return found->second;
    PipelineSet set;
    for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
        for (int blended = 0; blended < 2; ++blended) {
            gpu::GraphicsPipelineDesc desc;
            desc.vertexShader = "mesh.vert";
            desc.fragmentShader = target.fragmentShader;
            desc.bindings = inputs.bindings;
            desc.textureTable = scene_.textureTable();
            desc.colorFormats = {target.colorFormat};
            desc.depthFormat = gpu::Format::D32Float;
            desc.depthCompare = gpu::CompareOp::GreaterOrEqual;  // reversed Z
            desc.depthWrite = !blended;
            desc.cullMode = doubleSided ? gpu::CullMode::None : gpu::CullMode::Back;
            desc.blend = blended ? gpu::BlendMode::Alpha : gpu::BlendMode::Opaque;
            desc.specialization = {{1, uint32_t(blended)}};
            desc.specialization.insert(desc.specialization.end(), target.specialization.begin(),
                                       target.specialization.end());
            (blended ? set.blended : set.opaque)[doubleSided] = device_.createGraphicsPipeline(desc);
        }
    }
    return pipelineSets_.emplace(key, set).first->second;
}

void MainPass::drawItems(gpu::CommandList& commands, const std::vector<const DrawItem*>& items, const PipelineSet& set,
                         bool blended, const Scene& scene, const std::vector<gpu::DescriptorWrite>& writes) {
    int boundVariant = -1;
    for (const DrawItem* item : items) {
        const int doubleSided = scene.materials.at(item->materialIndex).doubleSided ? 1 : 0;
        if (doubleSided != boundVariant) {
            commands.bindPipeline((blended ? set.blended : set.opaque)[doubleSided]);
            commands.pushDescriptors(writes);
            commands.bindTextureTable(scene_.textureTable());
            commands.bindIndexBuffer(scene_.indexBuffer());
            boundVariant = doubleSided;
        }
        commands.drawIndexed(item->indexCount, 1, item->firstIndex, item->vertexOffset, item->instanceIndex);
    }
}

void MainPass::record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                      const MainPassInputs& inputs, const Target& target) {
    const PipelineSet& set = pipelines(target, inputs);
    const std::vector<gpu::DescriptorWrite>& writes = inputs.writes;

    std::vector<const DrawItem*> opaque, blended;
    for (const DrawItem& item : scene_.draws()) {
        const bool isBlend = scene.materials.at(item.materialIndex).alphaMode == AlphaMode::Blend;
        if (!isBlend) opaque.push_back(&item);
        else if (target.drawBlended) blended.push_back(&item);
    }
    // Transparent draws back to front by the distance of their bounds' centre to the camera.
    auto distance = [&](const DrawItem* item) {
        return glm::length(scene.instances[item->instanceIndex].wsBounds.center() - view.wsPosition);
    };
    std::stable_sort(blended.begin(), blended.end(), [&](auto* a, auto* b) { return distance(a) > distance(b); });

    gpu::RenderingDesc rendering;
    rendering.width = view.width;
    rendering.height = view.height;
    gpu::ColorAttachment color;
    color.texture = target.color;
    std::copy(target.clearColor, target.clearColor + 4, color.clearColor);
    rendering.colors = {color};
    rendering.depth = {target.depth, true, 0.0f};
    commands.beginRendering(rendering);
    drawItems(commands, opaque, set, false, scene, writes);
    drawItems(commands, blended, set, true, scene, writes);
    commands.endRendering();
}

}  // namespace penumbra
