#include "render/light_cluster_pass.h"

#include <cstring>

#include "light_cluster_structs.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"

namespace penumbra {

LightClusterPass::LightClusterPass(gpu::Device& device) : device_(device) {
    try {
        create();
    } catch (...) {
        destroyAll();  // a failed allocation half-way: the destructor does not run
        throw;
    }
}

void LightClusterPass::create() {
    gpu::ComputePipelineDesc desc;
    desc.shader = "light_cluster.comp";
    desc.bindings = lightClusterBindings();
    desc.debugName = "light clusters";
    pipeline_ = device_.createComputePipeline(desc);
    const uint64_t maskBytes = uint64_t(gpu_data::kClusterCount) * gpu_data::kMaxClusterLightWords * 4;
    masks_ = device_.createBuffer(maskBytes, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal, nullptr,
                                  "light cluster masks");
    stats_ = device_.createBuffer(sizeof(gpu_data::LightClusterStats), gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal,
                                  nullptr, "light cluster stats");
}

LightClusterPass::~LightClusterPass() { destroyAll(); }

void LightClusterPass::destroyAll() {
    device_.destroy(pipeline_);
    device_.destroy(masks_);
    device_.destroy(stats_);
}

void LightClusterPass::record(gpu::CommandList& commands, const gpu::BufferSlice& clusters,
                              const gpu::BufferSlice& lights, bool clustered) {
    commands.pass("lightClusters/clear", {gpu::use(stats_, gpu::Usage::TransferWrite)});
    commands.clearBuffer(stats_, 0);
    if (!clustered) return;
    commands.pass("lightClusters", {gpu::use(masks_, gpu::Usage::ComputeWrite), gpu::use(stats_, gpu::Usage::ComputeWrite)});
    commands.bindPipeline(pipeline_);
    const gpu::DescriptorWrite writes[] = {{gpu_data::kSceneBindingLights, lights},
                                                      {gpu_data::kLitBindingLightClusters, clusters},
                                                      {gpu_data::kLitBindingClusterMasks, masks_, {}, {}},
                                                      {gpu_data::kClusterBindingStats, stats_, {}, {}}};
    commands.pushDescriptors(writes);
    commands.dispatch(gpu_data::kClusterCount, 1);  // a workgroup per cluster, an invocation per mask word
}

gpu::BufferSlice LightClusterPass::stats() const { return {stats_, 0, sizeof(gpu_data::LightClusterStats)}; }

std::vector<uint32_t> LightClusterPass::readMasks(uint32_t words) {
    const std::vector<uint8_t> bytes = device_.readBuffer(masks_);
    std::vector<uint32_t> masks(size_t(gpu_data::kClusterCount) * words);
    std::memcpy(masks.data(), bytes.data(), masks.size() * 4);
    return masks;
}

}  // namespace penumbra
