#include "render/atlas_copy_pass.h"

#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

AtlasCopyPass::AtlasCopyPass(gpu::Device& device) : device_(device) {
    try {
        gpu::ComputePipelineDesc desc;
        desc.pushConstantSize = sizeof(gpu_data::AtlasCopyConstants);
        desc.shader = desc.debugName = "shadow_atlas_copy.comp";
        desc.bindings = atlasCopyBindings(desc.shader);
        fromBuffer_ = device.createComputePipeline(desc);
        desc.shader = desc.debugName = "shadow_atlas_resolve.comp";
        desc.bindings = atlasCopyBindings(desc.shader);
        fromImage_ = device.createComputePipeline(desc);
        pointSampler_ = device.createSampler({gpu::Filter::Nearest, false, gpu::AddressMode::ClampToEdge});
    } catch (...) {
        release();  // a failed creation half-way: the destructor does not run
        throw;
    }
}

AtlasCopyPass::~AtlasCopyPass() { release(); }

void AtlasCopyPass::release() {
    device_.destroy(fromBuffer_);
    device_.destroy(fromImage_);
    device_.destroy(pointSampler_);
    fromBuffer_ = fromImage_ = {};
    pointSampler_ = {};
}

void AtlasCopyPass::copyFromBuffer(gpu::CommandList& commands, std::string_view name, gpu::BufferHandle depth,
                                   gpu::TextureHandle atlas, uint32_t atlasSize, std::span<const gpu::Rect> rects, bool fresh) {
    const gpu::BufferSlice texels{depth, 0, uint64_t(atlasSize) * atlasSize * 4};
    copy(commands, name, fromBuffer_, gpu::use(depth, gpu::Usage::ComputeRead), {gpu_data::kAtlasCopyBindingDepth, texels},
         {atlas, atlasSize, rects, fresh});
}

void AtlasCopyPass::copyFromImage(gpu::CommandList& commands, std::string_view name, gpu::TextureHandle depth,
                                  gpu::TextureHandle atlas, uint32_t atlasSize, std::span<const gpu::Rect> rects, bool fresh) {
    copy(commands, name, fromImage_, gpu::use(depth, gpu::Usage::ComputeSampled),
         {gpu_data::kAtlasCopyBindingSource, {}, depth, pointSampler_}, {atlas, atlasSize, rects, fresh});
}

void AtlasCopyPass::copy(gpu::CommandList& commands, std::string_view name, gpu::PipelineHandle pipeline,
                         const gpu::ResourceUse& sourceUse, const gpu::DescriptorWrite& sourceWrite, const Target& target) {
    if (target.rects.empty() && !target.fresh) return;
    commands.beginTimer(name);
    commands.pass(name, {sourceUse, target.fresh ? gpu::discard(target.atlas, gpu::Usage::ComputeWrite)
                                                 : gpu::use(target.atlas, gpu::Usage::ComputeWrite)});
    commands.bindPipeline(pipeline);
    const gpu::DescriptorWrite writes[] = {sourceWrite, {gpu_data::kAtlasCopyBindingAtlas, {}, target.atlas, {}}};
    commands.pushDescriptors(writes);
    dispatchRects(commands, target);
    commands.endTimer();
}

void AtlasCopyPass::dispatchRects(gpu::CommandList& commands, const Target& target) {
    const uint32_t atlasSize = target.atlasSize;
    const gpu::Rect whole{0, 0, atlasSize, atlasSize};
    const std::span<const gpu::Rect> copied = target.fresh ? std::span(&whole, 1) : target.rects;
    constexpr uint32_t groupX = gpu_data::kAtlasCopyGroupX, groupY = gpu_data::kAtlasCopyGroupY;
    for (const gpu::Rect& rect : copied) {
        const gpu_data::AtlasCopyConstants constants{uint32_t(rect.x), uint32_t(rect.y), rect.width, rect.height, atlasSize, 0, 0, 0};
        commands.pushConstants(&constants, sizeof(constants));
        commands.dispatch((rect.width + groupX - 1) / groupX, (rect.height + groupY - 1) / groupY);
    }
}

}  // namespace penumbra
