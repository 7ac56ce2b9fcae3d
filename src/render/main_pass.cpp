#include "render/main_pass.h"

#include "core/error.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

#include <algorithm>
#include <span>

namespace penumbra {

SceneWrites sceneDescriptorWrites(const GpuScene& gpuScene, const gpu::BufferSlice& frame,
                                  const gpu::BufferSlice& lights) {
    using namespace gpu_data;
    return {{{kSceneBindingFrame, frame}, {kSceneBindingVertices, gpuScene.vertexBuffer(), {}, {}},
            {kSceneBindingInstances, gpuScene.instanceBuffer(), {}, {}},
            {kSceneBindingMaterials, gpuScene.materialBuffer(), {}, {}}, {kSceneBindingLights, lights}}};
}

void addShadingReads(std::vector<gpu::ResourceUse>& uses, const GpuScene& scene, const MainPassInputs& inputs,
                     bool compute) {
    using gpu::Usage;
    scene.addSceneReads(uses, compute ? Usage::ComputeRead : Usage::GraphicsRead);
    for (gpu::TextureHandle texture : inputs.sampled)
        uses.push_back(gpu::use(texture, compute ? Usage::ComputeSampled : Usage::FragmentSampled));
    for (gpu::BufferHandle buffer : {inputs.clusterMasks, inputs.virtualPages[0], inputs.virtualPages[1]})
        if (buffer) uses.push_back(gpu::use(buffer, compute ? Usage::ComputeRead : Usage::GraphicsRead));
}

MainPass::~MainPass() {
    for (auto& [key, set] : pipelineSets_)
        for (auto& byBlend : set.pipelines)
            for (gpu::PipelineHandle p : byBlend) device_.destroy(p);
    for (auto& [format, pipeline] : backgrounds_) device_.destroy(pipeline);
    device_.destroy(opaqueCommands_);
    device_.destroy(opaqueCounts_);
}

bool MainPass::VariantLess::operator()(const MainPassVariant& a, const MainPassVariant& b) const {
    if (std::tie(a.colorFormat, a.fragmentShader, a.drawBlended) != std::tie(b.colorFormat, b.fragmentShader, b.drawBlended))
        return std::tie(a.colorFormat, a.fragmentShader, a.drawBlended) < std::tie(b.colorFormat, b.fragmentShader, b.drawBlended);
    return std::lexicographical_compare(
        a.specialization.begin(), a.specialization.end(), b.specialization.begin(), b.specialization.end(),
        [](const gpu::SpecConstant& x, const gpu::SpecConstant& y) { return std::tie(x.id, x.value) < std::tie(y.id, y.value); });
}

MainPass::PipelineSet& MainPass::create(const MainPassVariant& variant, bool async) {
    PipelineSet& set = pipelineSets_.emplace(variant, PipelineSet{}).first->second;
    completeSet(variant, set, async);
    // The colour output's sets come with the background of their format (built alongside, so a
    // change of render.background builds nothing).
    if (variant.drawBlended) backgroundPipeline(variant.colorFormat, async);
    return set;
}

void MainPass::completeSet(const MainPassVariant& variant, PipelineSet& set, bool async) {
    for (int blended = 0; blended < (variant.drawBlended ? 2 : 1); ++blended) {
        for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
            if (!slotsUsed_[blended][doubleSided] || set.pipelines[blended][doubleSided]) continue;
            gpu::GraphicsPipelineDesc desc;
            desc.vertexShader = "mesh.vert";
            desc.fragmentShader = variant.fragmentShader;
            desc.bindings = mainPassBindings(variant.fragmentShader);
            desc.textureTable = scene_.textureTable();
            desc.colorFormats = {variant.colorFormat};
            desc.depthFormat = gpu::Format::D32Float;
            desc.depthCompare = gpu::CompareOp::GreaterOrEqual;  // reversed Z
            desc.depthWrite = !blended;
            desc.cullMode = doubleSided ? gpu::CullMode::None : gpu::CullMode::Back;
            desc.blend = blended ? gpu::BlendMode::Alpha : gpu::BlendMode::Opaque;
            desc.specialization = {{1, uint32_t(blended)}};
            desc.specialization.insert(desc.specialization.end(), variant.specialization.begin(),
                                       variant.specialization.end());
            desc.debugName = variant.fragmentShader + (blended ? " blended" : "") + (doubleSided ? " double-sided" : "");
            set.pipelines[blended][doubleSided] =
                async ? device_.createGraphicsPipelineAsync(desc) : device_.createGraphicsPipeline(desc);
        }
    }
}

gpu::PipelineHandle MainPass::backgroundPipeline(gpu::Format colorFormat, bool async) {
    if (const auto found = backgrounds_.find(colorFormat); found != backgrounds_.end()) return found->second;
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "fullscreen.vert";  // at depth 0: reversed Z's far end, the depth buffer's clear value
    desc.fragmentShader = "background.frag";
    desc.bindings = backgroundBindings();
    desc.colorFormats = {colorFormat};
    desc.depthFormat = gpu::Format::D32Float;
    desc.depthCompare = gpu::CompareOp::GreaterOrEqual;  // passes only where the depth is still cleared
    desc.depthWrite = false;
    desc.cullMode = gpu::CullMode::None;
    desc.debugName = "background";
    const gpu::PipelineHandle pipeline = async ? device_.createGraphicsPipelineAsync(desc) : device_.createGraphicsPipeline(desc);
    backgrounds_.emplace(colorFormat, pipeline);
    return pipeline;
}

void MainPass::drawBackground(gpu::CommandList& commands, const Target& target,
                              const std::vector<gpu::DescriptorWrite>& writes) {
    const gpu::PipelineHandle pipeline = backgroundPipeline(target.variant.colorFormat, false);
    device_.waitForPipeline(pipeline);  // only before its first build has finished
    const auto frame = std::find_if(writes.begin(), writes.end(), [](const auto& w) { return w.binding == gpu_data::kSceneBindingFrame; });
    PENUMBRA_ASSERT(frame != writes.end());
    commands.bindPipeline(pipeline);
    commands.pushDescriptors(std::span(&*frame, 1));
    commands.draw(3);
}

bool MainPass::setReady(const PipelineSet& set) {
    for (const auto& byBlend : set.pipelines)
        for (gpu::PipelineHandle p : byBlend)
            if (p && !device_.pipelineReady(p)) return false;
    return true;
}

void MainPass::waitFor(const PipelineSet& set) {
    for (const auto& byBlend : set.pipelines)
        for (gpu::PipelineHandle p : byBlend)
            if (p) device_.waitForPipeline(p);
}

void MainPass::request(const MainPassVariant& variant) {
    if (pipelineSets_.count(variant) == 0) create(variant, warmup_ == PipelineWarmup::Background);
}

bool MainPass::ready(const MainPassVariant& variant) {
    const auto found = pipelineSets_.find(variant);
    return found != pipelineSets_.end() && setReady(found->second);
}

const MainPass::PipelineSet& MainPass::pipelinesFor(const Target& target) {
    request(target.variant);
    PipelineSet& wanted = pipelineSets_.at(target.variant);
    completeSet(target.variant, wanted, false);  // only after a material made a new combination appear
    if (setReady(wanted)) return wanted;
    // A CPU device (lavapipe) compiles a fragment shader when it is first drawn, not when its pipeline is
    // made: drawing the generic stand-in would not spare this frame a wait but add the largest compile of
    // all. It waits for the variant it wants.
    if (!target.genericSpecialization.empty() && !device_.info().isCpu) {
        MainPassVariant generic = target.variant;
        generic.specialization = target.genericSpecialization;
        request(generic);
        PipelineSet& fallback = pipelineSets_.at(generic);
        completeSet(generic, fallback, false);
        waitFor(fallback);  // only before the generic set's first build has finished
        return fallback;
    }
    waitFor(wanted);
    return wanted;
}

void MainPass::bindDrawState(gpu::CommandList& commands, gpu::PipelineHandle pipeline,
                             const std::vector<gpu::DescriptorWrite>& writes) {
    commands.bindPipeline(pipeline);
    commands.pushDescriptors(writes);
    commands.bindTextureTable(scene_.textureTable());
    commands.bindIndexBuffer(scene_.indexBuffer());
}

void MainPass::drawItems(gpu::CommandList& commands, const std::vector<const DrawItem*>& items, const PipelineSet& set,
                         bool blended, const Scene& scene, const std::vector<gpu::DescriptorWrite>& writes) {
    int boundVariant = -1;
    for (const DrawItem* item : items) {
        const int doubleSided = scene.materials.at(item->materialIndex).doubleSided ? 1 : 0;
        if (doubleSided != boundVariant) {
            bindDrawState(commands, set.pipelines[blended ? 1 : 0][doubleSided], writes);
            boundVariant = doubleSided;
        }
        commands.drawIndexed(item->indexCount, 1, item->firstIndex, item->vertexOffset, item->instanceIndex);
    }
}

void MainPass::drawOpaque(gpu::CommandList& commands, const PipelineSet& set, const std::vector<gpu::DescriptorWrite>& writes) {
    uint32_t first = 0;
    for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
        const uint32_t count = opaqueCountBySide_[doubleSided];
        if (count == 0) continue;
        bindDrawState(commands, set.pipelines[0][doubleSided], writes);
        commands.drawIndexedIndirectCount(opaqueCommands_, uint64_t(first) * sizeof(gpu::IndexedDrawCommand),
                                          opaqueCounts_, uint64_t(doubleSided) * sizeof(uint32_t), count);
        first += count;
    }
}

void MainPass::partitionDraws(const Scene& scene) {
    opaqueDraws_.clear();
    blendedDraws_.clear();
    for (const DrawItem& item : scene_.draws()) {
        const Material& material = scene.materials.at(item.materialIndex);
        const bool blended = material.alphaMode == AlphaMode::Blend;
        (blended ? blendedDraws_ : opaqueDraws_).push_back(&item);
        slotsUsed_[blended ? 1 : 0][material.doubleSided ? 1 : 0] = true;  // never unset: the pipeline stays
    }
    auto singleSided = [&](const DrawItem* item) { return !scene.materials[item->materialIndex].doubleSided; };
    const auto split = std::stable_partition(opaqueDraws_.begin(), opaqueDraws_.end(), singleSided);
    uploadOpaqueCommands({uint32_t(split - opaqueDraws_.begin()), uint32_t(opaqueDraws_.end() - split)});
}

void MainPass::uploadOpaqueCommands(std::array<uint32_t, 2> countBySide) {
    gpu::BufferHandle commands, counts;
    if (!opaqueDraws_.empty()) {
        std::vector<gpu::IndexedDrawCommand> data;
        data.reserve(opaqueDraws_.size());
        for (const DrawItem* item : opaqueDraws_)
            data.push_back({item->indexCount, 1, item->firstIndex, item->vertexOffset, item->instanceIndex});
        using gpu::MemoryKind;
        commands = device_.createBuffer(data.size() * sizeof(data[0]), gpu::kBufferIndirect, MemoryKind::DeviceLocal,
                                        data.data(), "main pass opaque draws");
        try {
            counts = device_.createBuffer(sizeof(countBySide), gpu::kBufferIndirect, MemoryKind::DeviceLocal,
                                          countBySide.data(), "main pass opaque draw counts");
        } catch (...) {
            device_.destroy(commands);  // this pass's destructor does not run when its constructor throws
            throw;
        }
    }
    device_.destroy(opaqueCommands_);  // deferred: a frame in flight may still read them
    device_.destroy(opaqueCounts_);
    opaqueCommands_ = commands;
    opaqueCounts_ = counts;
    opaqueCountBySide_ = countBySide;  // with the buffers: a failed upload keeps the last ones and their counts
}

void MainPass::record(gpu::CommandList& commands, const Scene& scene, const CameraView& view,
                      const MainPassInputs& inputs, const Target& target) {
    const PipelineSet& set = pipelinesFor(target);
    // The opaque draws by two indirect multi-draws where the device allows that many draws per call.
    const bool multiDraw = device_.maxDrawIndirectCount() >= std::max(opaqueCountBySide_[0], opaqueCountBySide_[1]);
    static const std::vector<const DrawItem*> none;
    const std::vector<const DrawItem*>& opaque = target.opaqueDone || multiDraw ? none : opaqueDraws_;
    std::vector<const DrawItem*>& blended = blended_;  // a member: its storage is reused frame to frame
    blended.clear();
    if (target.variant.drawBlended) blended.assign(blendedDraws_.begin(), blendedDraws_.end());
    // Transparent draws back to front by the distance of their bounds' centre to the camera, equal
    // distances in scene order (std::sort with that tie-break: stable_sort would allocate a buffer).
    auto distance = [&](const DrawItem* item) {
        return glm::length(scene.instances[item->instanceIndex].wsBounds.center() - view.wsPosition);
    };
    std::sort(blended.begin(), blended.end(), [&](auto* a, auto* b) {
        const float da = distance(a), db = distance(b);
        return da != db ? da > db : a < b;
    });

    gpu::RenderingDesc& rendering = rendering_;
    rendering.width = target.width;
    rendering.height = target.height;
    gpu::ColorAttachment color;
    color.texture = target.color;
    color.clear = !target.opaqueDone;
    std::copy(target.clearColor, target.clearColor + 4, color.clearColor);
    rendering.colors = std::span(&color, 1);
    rendering.depth = {target.depth, !target.opaqueDone, 0.0f};
    using gpu::Usage;
    std::vector<gpu::ResourceUse>& uses = uses_;
    if (target.opaqueDone) {
        uses = {gpu::use(target.color, Usage::ColorTarget), gpu::use(target.depth, Usage::DepthTarget)};
    } else {  // cleared
        uses = {gpu::discard(target.color, Usage::ColorTarget), gpu::discard(target.depth, Usage::DepthTarget)};
    }
    uses.push_back(gpu::use(scene_.indexBuffer(), Usage::IndexBuffer));
    if (!target.opaqueDone && multiDraw && opaqueCommands_) {
        uses.push_back(gpu::use(opaqueCommands_, Usage::IndirectArguments));
        uses.push_back(gpu::use(opaqueCounts_, Usage::IndirectArguments));
    }
    addShadingReads(uses, scene_, inputs, false);
    commands.pass(target.passName, uses);
    commands.beginRendering(rendering);
    if (!target.opaqueDone && multiDraw) drawOpaque(commands, set, inputs.writes);
    drawItems(commands, opaque, set, false, scene, inputs.writes);
    if (target.background) drawBackground(commands, target, inputs.writes);
    drawItems(commands, blended, set, true, scene, inputs.writes);
    commands.endRendering();
}

}  // namespace penumbra
