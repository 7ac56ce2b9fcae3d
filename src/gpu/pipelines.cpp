// Graphics and compute pipelines: shader modules from the embedded SPIR-V, a push-descriptor set 0,
// an optional texture-table set 1, push constants, specialization constants, dynamic rendering.
#include <algorithm>

#include "gpu/shader_interface.h"
#include "gpu/shader_registry.h"
#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

VkDescriptorType toVkDescriptorType(DescriptorType type) {
    switch (type) {
        case DescriptorType::UniformBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        case DescriptorType::StorageBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        case DescriptorType::SampledTexture: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        case DescriptorType::StorageTexture: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
    return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

VkShaderStageFlags toVkShaderStages(uint32_t stages) {
    VkShaderStageFlags flags = 0;
    if (stages & kStageVertex) flags |= VK_SHADER_STAGE_VERTEX_BIT;
    if (stages & kStageFragment) flags |= VK_SHADER_STAGE_FRAGMENT_BIT;
    if (stages & kStageCompute) flags |= VK_SHADER_STAGE_COMPUTE_BIT;
    return flags;
}

std::vector<PipelineStage> pipelineStages(const GraphicsPipelineDesc& desc) {
    std::vector<PipelineStage> stages = {{kStageVertex, desc.vertexShader}};
    if (!desc.fragmentShader.empty()) stages.push_back({kStageFragment, desc.fragmentShader});
    return stages;
}
std::vector<PipelineStage> pipelineStages(const ComputePipelineDesc& desc) { return {{kStageCompute, desc.shader}}; }

// The pass's declaration against the shaders' SPIR-V (shader_interface.h); throws Error.
template <typename Desc>
void checkInterface(const Desc& desc) {
    checkPipelineInterface(desc.debugName, pipelineStages(desc), desc.bindings, desc.pushConstantSize,
                           bool(desc.textureTable));
}

// The push-constant range's stages: the shaders whose SPIR-V uses the block (every stage of the
// pipeline when none does, as a range needs one).
template <typename Desc>
VkShaderStageFlags pushConstantStages(const Desc& desc) {
    uint32_t used = 0, all = 0;
    for (const PipelineStage& stage : pipelineStages(desc)) {
        all |= stage.stage;
        if (embeddedShaderInterface(stage.shader).pushConstantSize) used |= stage.stage;
    }
    return toVkShaderStages(used ? used : all);
}

// Specialization data outlives the create call through this holder.
struct Specialization {
    std::vector<VkSpecializationMapEntry> entries;
    std::vector<uint32_t> values;
    VkSpecializationInfo info{};

    Specialization(const std::vector<SpecConstant>& constants, uint32_t textureCount) {
        auto add = [&](uint32_t id, uint32_t value) {
            entries.push_back({id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
            values.push_back(value);
        };
        if (textureCount) add(0, textureCount);  // constant 0: size of the texture table
        for (const SpecConstant& c : constants) add(c.id, c.value);
        info.mapEntryCount = uint32_t(entries.size());
        info.pMapEntries = entries.data();
        info.dataSize = values.size() * sizeof(uint32_t);
        info.pData = values.data();
    }
};

void createLayout(Device::Impl& d, PipelineResource& p, const std::vector<BindingDesc>& bindings,
                  uint32_t pushConstantSize, TextureTableHandle table) {
    // p.pushStages is set by the caller (pushConstantStages).
    std::vector<VkDescriptorSetLayoutBinding> vkBindings;
    for (const BindingDesc& b : bindings)
        vkBindings.push_back({b.binding, toVkDescriptorType(b.type), b.count, toVkShaderStages(b.stages), nullptr});
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(vkBindings.size());
    setInfo.pBindings = vkBindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(d.device, &setInfo, nullptr, &p.pushSetLayout));
    VkDescriptorSetLayout setLayouts[2] = {p.pushSetLayout, VK_NULL_HANDLE};
    if (table) setLayouts[1] = d.tables.at(table.id).layout;
    VkPushConstantRange range{p.pushStages, 0, pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = table ? 2 : 1;
    layoutInfo.pSetLayouts = setLayouts;
    layoutInfo.pushConstantRangeCount = pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(d.device, &layoutInfo, nullptr, &p.layout));
    p.bindings = bindings;
}

}  // namespace

VkCompareOp toVkCompareOp(CompareOp op) {
    static const VkCompareOp ops[] = {VK_COMPARE_OP_NEVER, VK_COMPARE_OP_LESS, VK_COMPARE_OP_LESS_OR_EQUAL,
                                      VK_COMPARE_OP_GREATER, VK_COMPARE_OP_GREATER_OR_EQUAL, VK_COMPARE_OP_ALWAYS};
    return ops[int(op)];
}

VkShaderModule Device::Impl::loadShader(const std::string& name) {
    const std::span<const uint32_t> code = embeddedShader(name);
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = code.size_bytes();
    info.pCode = code.data();
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

VkPipeline Device::Impl::buildGraphicsPipeline(const GraphicsPipelineDesc& desc, VkPipelineLayout layout,
                                               uint32_t textureCount) {
    Specialization specialization(desc.specialization, textureCount);
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    auto addStage = [&](VkShaderStageFlagBits stage, const std::string& name) {
        VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        s.stage = stage;
        s.module = loadShader(name);
        s.pName = "main";
        s.pSpecializationInfo = &specialization.info;
        stages.push_back(s);
    };
    addStage(VK_SHADER_STAGE_VERTEX_BIT, desc.vertexShader);
    if (!desc.fragmentShader.empty()) addStage(VK_SHADER_STAGE_FRAGMENT_BIT, desc.fragmentShader);

    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.depthClampEnable = desc.depthClamp;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = desc.cullMode == CullMode::Back ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
    // glTF front faces are CCW as seen by the viewer; the y-flipped projection shows the image upright
    // on Vulkan's y-down framebuffer, so they stay counter-clockwise there.
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.depthBiasEnable = desc.dynamicDepthBias;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depthTest;
    depth.depthWriteEnable = desc.depthWrite;
    depth.depthCompareOp = toVkCompareOp(desc.depthCompare);
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (auto& b : blends) {
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        if (desc.blend == BlendMode::Alpha) {
            b.blendEnable = VK_TRUE;
            b.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
            b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            b.colorBlendOp = VK_BLEND_OP_ADD;
            b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            b.alphaBlendOp = VK_BLEND_OP_ADD;
        }
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = uint32_t(blends.size());
    blend.pAttachments = blends.data();
    std::vector<VkDynamicState> dynamicStates = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    if (desc.dynamicDepthBias) dynamicStates.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = uint32_t(dynamicStates.size());
    dynamic.pDynamicStates = dynamicStates.data();

    std::vector<VkFormat> colorFormats;
    for (Format f : desc.colorFormats) colorFormats.push_back(toVkFormat(f));
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(colorFormats.size());
    rendering.pColorAttachmentFormats = colorFormats.data();
    rendering.depthAttachmentFormat = toVkFormat(desc.depthFormat);

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = uint32_t(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    ++pipelinesCompiled;
    const VkResult result = vkCreateGraphicsPipelines(device, pipelineCache, 1, &info, nullptr, &pipeline);
    for (auto& stage : stages) vkDestroyShaderModule(device, stage.module, nullptr);
    if (result != VK_SUCCESS)
        throw Error("Vulkan call failed: vkCreateGraphicsPipelines (" + desc.debugName + ") returned " + vkResultName(result));
    setDebugName(VK_OBJECT_TYPE_PIPELINE, uint64_t(pipeline), desc.debugName.empty() ? desc.fragmentShader : desc.debugName);
    return pipeline;
}

namespace {

uint32_t tableSize(Device::Impl& d, TextureTableHandle table) { return table ? d.tables.at(table.id).count : 0; }

}  // namespace

PipelineHandle Device::createGraphicsPipeline(const GraphicsPipelineDesc& desc) {
    Impl& d = *impl_;
    checkInterface(desc);
    PipelineResource p;
    const uint32_t textureCount = tableSize(d, desc.textureTable);
    const std::string key = Impl::reuseKey(desc, textureCount);
    p.pushStages = pushConstantStages(desc);
    if (d.takeParkedPipeline(key, p)) {
        p.bindings = desc.bindings;
    } else {
        createLayout(d, p, desc.bindings, desc.pushConstantSize, desc.textureTable);
        p.reuseKey = key;
        try {
            p.pipeline = d.buildGraphicsPipeline(desc, p.layout, textureCount);
        } catch (...) {
            d.destroyNow(p);
            throw;
        }
    }
    p.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    d.noteCreated(desc.debugName.empty() ? desc.fragmentShader : desc.debugName);
    return PipelineHandle{d.pipelines.insert(std::move(p))};
}

PipelineHandle Device::createGraphicsPipelineAsync(const GraphicsPipelineDesc& desc) {
    Impl& d = *impl_;
    checkInterface(desc);
    PipelineResource p;
    const uint32_t textureCount = tableSize(d, desc.textureTable);
    const std::string key = Impl::reuseKey(desc, textureCount);
    p.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    p.pushStages = pushConstantStages(desc);
    d.noteCreated(desc.debugName.empty() ? desc.fragmentShader : desc.debugName);
    if (d.takeParkedPipeline(key, p)) {  // compiled already: ready at once
        p.bindings = desc.bindings;
        return PipelineHandle{d.pipelines.insert(std::move(p))};
    }
    createLayout(d, p, desc.bindings, desc.pushConstantSize, desc.textureTable);
    p.reuseKey = key;
    const VkPipelineLayout layout = p.layout;
    const uint32_t id = d.pipelines.insert(std::move(p));
    {
        std::lock_guard lock(d.jobsMutex);
        d.jobs.push_back({id, desc, layout, textureCount});
    }
    d.jobsChanged.notify_all();
    return PipelineHandle{id};
}

bool Device::pipelineReady(PipelineHandle pipeline) {
    impl_->collectPipelineBuilds();
    return impl_->pipelines.at(pipeline.id).pipeline != VK_NULL_HANDLE;
}

void Device::waitForPipeline(PipelineHandle pipeline) {
    Impl& d = *impl_;
    {  // still queued behind a warm-up's builds: it goes first
        std::lock_guard lock(d.jobsMutex);
        const auto queued = std::find_if(d.jobs.begin(), d.jobs.end(), [&](const auto& job) { return job.id == pipeline.id; });
        if (queued != d.jobs.end() && queued != d.jobs.begin()) {
            auto job = std::move(*queued);
            d.jobs.erase(queued);
            d.jobs.push_front(std::move(job));
        }
    }
    while (!pipelineReady(pipeline)) {
        std::unique_lock lock(d.jobsMutex);
        if (!d.buildErrors.empty()) break;
        d.jobsChanged.wait_for(lock, std::chrono::milliseconds(50));
    }
    d.collectPipelineBuilds();
}

uint32_t Device::pipelineBuildsPending() {
    Impl& d = *impl_;
    d.collectPipelineBuilds();
    std::lock_guard lock(d.jobsMutex);
    return uint32_t(d.jobs.size()) + d.buildsRunning;
}

void Device::waitForPipelineBuilds() {
    Impl& d = *impl_;
    {
        std::unique_lock lock(d.jobsMutex);
        d.jobsChanged.wait(lock, [&] { return (d.jobs.empty() && d.buildsRunning == 0) || !d.buildErrors.empty(); });
    }
    d.collectPipelineBuilds();
}

void Device::Impl::collectPipelineBuilds() {
    std::vector<std::pair<uint32_t, VkPipeline>> finished;
    std::vector<std::string> errors;
    {
        std::lock_guard lock(jobsMutex);
        finished.swap(finishedBuilds);
        errors.swap(buildErrors);
    }
    for (auto [id, pipeline] : finished) {
        if (pipelines.contains(id) && !pipelines.at(id).pipeline) pipelines.at(id).pipeline = pipeline;
        else vkDestroyPipeline(device, pipeline, nullptr);  // destroyed before its build finished
    }
    if (!errors.empty()) throw Error(errors.front());
}

void Device::Impl::startWorker() {
    worker = std::thread([this] {
        std::unique_lock lock(jobsMutex);
        while (true) {
            jobsChanged.wait(lock, [&] { return stopWorker || !jobs.empty(); });
            if (stopWorker) return;
            PipelineJob job = std::move(jobs.front());
            jobs.pop_front();
            ++buildsRunning;
            lock.unlock();
            VkPipeline pipeline = VK_NULL_HANDLE;
            std::string error;
            try {
                pipeline = buildGraphicsPipeline(job.desc, job.layout, job.textureCount);
            } catch (const std::exception& e) {
                error = e.what();
            }
            lock.lock();
            --buildsRunning;
            if (pipeline) finishedBuilds.emplace_back(job.id, pipeline);
            else buildErrors.push_back(error);
            jobsChanged.notify_all();
        }
    });
}

void Device::Impl::stopWorkerThread() {
    {
        std::lock_guard lock(jobsMutex);
        stopWorker = true;
        jobs.clear();
    }
    jobsChanged.notify_all();
    if (worker.joinable()) worker.join();
    for (auto [id, pipeline] : finishedBuilds) {
        if (pipelines.contains(id) && !pipelines.at(id).pipeline) pipelines.at(id).pipeline = pipeline;
        else vkDestroyPipeline(device, pipeline, nullptr);
    }
    finishedBuilds.clear();
}

void Device::Impl::destroyNow(PipelineResource& p) {
    if (p.layout) {
        // A background build may still use the layout (a renderer destroyed while its variants build):
        // drop the queued ones and let the running one finish first.
        std::unique_lock lock(jobsMutex);
        std::erase_if(jobs, [&](const PipelineJob& job) { return job.layout == p.layout; });
        jobsChanged.wait(lock, [&] { return buildsRunning == 0; });
    }
    if (p.pipeline) vkDestroyPipeline(device, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(device, p.layout, nullptr);
    if (p.pushSetLayout) vkDestroyDescriptorSetLayout(device, p.pushSetLayout, nullptr);
    p = PipelineResource{};
}

void Device::destroy(PipelineHandle handle) {
    Impl& d = *impl_;
    if (!handle) return;
    d.collectPipelineBuilds();
    // A build still running delivers its pipeline to a dead slot: collectPipelineBuilds destroys it.
    PipelineResource p = d.pipelines.remove(handle.id);
    {
        std::lock_guard lock(d.jobsMutex);
        std::erase_if(d.jobs, [&](const PipelineJob& job) { return job.id == handle.id; });
    }
    d.garbageList().pipelines.push_back(std::move(p));
}

PipelineHandle Device::createComputePipeline(const ComputePipelineDesc& desc) {
    Impl& d = *impl_;
    checkInterface(desc);
    PipelineResource p;
    const uint32_t textureCount = tableSize(d, desc.textureTable);
    const std::string key = Impl::reuseKey(desc, textureCount);
    p.pushStages = pushConstantStages(desc);
    if (d.takeParkedPipeline(key, p)) {
        p.bindings = desc.bindings;
        p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
        d.noteCreated(desc.debugName.empty() ? desc.shader : desc.debugName);
        return PipelineHandle{d.pipelines.insert(std::move(p))};
    }
    createLayout(d, p, desc.bindings, desc.pushConstantSize, desc.textureTable);
    p.reuseKey = key;
    ++d.pipelinesCompiled;
    Specialization specialization(desc.specialization, textureCount);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = d.loadShader(desc.shader);
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = &specialization.info;
    info.layout = p.layout;
    const VkResult result = vkCreateComputePipelines(d.device, d.pipelineCache, 1, &info, nullptr, &p.pipeline);
    vkDestroyShaderModule(d.device, info.stage.module, nullptr);
    if (result != VK_SUCCESS) {
        d.destroyNow(p);
        VK_CHECK(result);
    }
    const std::string& name = desc.debugName.empty() ? desc.shader : desc.debugName;
    d.setDebugName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline), name);
    p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    d.noteCreated(name);
    return PipelineHandle{d.pipelines.insert(std::move(p))};
}

}  // namespace penumbra::gpu
