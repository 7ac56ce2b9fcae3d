// Compiled pipelines outlive their handles: a destroyed pipeline that no frame uses any more is parked
// with its layouts, and the next pipeline created from the same description takes it instead of
// compiling again. Drivers compile at vkCreate*Pipelines (lavapipe, Mesa's CPU driver, spends most of
// a small one-shot render there), and a second Renderer on one device, a reloaded scene in the viewer
// or a settings round trip asks for pipelines it has already had. A parked pipeline is not a live
// object (Device::liveObjects); the device destroys the parked ones when it is destroyed.
#include <sstream>

#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

void appendLayout(std::ostringstream& key, const std::vector<BindingDesc>& bindings, uint32_t pushConstantSize,
                  uint32_t textureCount, const std::vector<SpecConstant>& specialization) {
    key << "|bindings";
    for (const BindingDesc& b : bindings) key << ' ' << b.binding << ':' << int(b.type) << ':' << b.stages;
    key << "|push " << pushConstantSize << "|textures " << textureCount << "|spec";
    for (const SpecConstant& c : specialization) key << ' ' << c.id << '=' << c.value;
}

// A parked pipeline is used by no frame and no background build: its objects go at once.
void destroyParked(VkDevice device, const ParkedPipeline& parked) {
    vkDestroyPipeline(device, parked.pipeline, nullptr);
    vkDestroyPipelineLayout(device, parked.layout, nullptr);
    vkDestroyDescriptorSetLayout(device, parked.pushSetLayout, nullptr);
}

}  // namespace

std::string Device::Impl::reuseKey(const GraphicsPipelineDesc& desc, uint32_t textureCount) {
    std::ostringstream key;
    key << "graphics|" << desc.vertexShader << '|' << desc.fragmentShader;
    appendLayout(key, desc.bindings, desc.pushConstantSize, textureCount, desc.specialization);
    key << "|colour";
    for (Format f : desc.colorFormats) key << ' ' << int(f);
    key << "|depth " << int(desc.depthFormat) << ' ' << desc.depthTest << desc.depthWrite << int(desc.depthCompare)
        << desc.depthClamp << desc.dynamicDepthBias << "|cull " << int(desc.cullMode) << "|blend " << int(desc.blend);
    return key.str();
}

std::string Device::Impl::reuseKey(const ComputePipelineDesc& desc, uint32_t textureCount) {
    std::ostringstream key;
    key << "compute|" << desc.shader;
    appendLayout(key, desc.bindings, desc.pushConstantSize, textureCount, desc.specialization);
    return key.str();
}

bool Device::Impl::takeParkedPipeline(const std::string& key, PipelineResource& p) {
    const auto found = parkedPipelines.find(key);
    if (found == parkedPipelines.end()) return false;
    p.pipeline = found->second.pipeline;
    p.layout = found->second.layout;
    p.pushSetLayout = found->second.pushSetLayout;
    p.reuseKey = key;
    parkedPipelines.erase(found);
    std::erase(parkedOrder, key);
    ++pipelinesReused;
    return true;
}

void Device::Impl::parkOrDestroy(PipelineResource& p) {
    if (!p.pipeline || p.reuseKey.empty() || parkedPipelines.contains(p.reuseKey)) {
        destroyNow(p);
        return;
    }
    if (parkedOrder.size() >= kMaxParkedPipelines) {
        destroyParked(device, parkedPipelines.at(parkedOrder.front()));
        parkedPipelines.erase(parkedOrder.front());
        parkedOrder.pop_front();
    }
    parkedPipelines.emplace(p.reuseKey, ParkedPipeline{p.pipeline, p.layout, p.pushSetLayout});
    parkedOrder.push_back(p.reuseKey);
    p = PipelineResource{};
}

void Device::Impl::destroyParkedPipelines() {
    for (const auto& [key, parked] : parkedPipelines) destroyParked(device, parked);
    parkedPipelines.clear();
    parkedOrder.clear();
}

}  // namespace penumbra::gpu
