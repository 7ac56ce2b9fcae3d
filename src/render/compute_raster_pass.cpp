#include "render/compute_raster_pass.h"

#include "cull_structs.h"
#include "render/main_pass.h"

namespace penumbra {

namespace {

constexpr uint32_t kFarDepthBits = 0x3f800000u;  // floatBitsToUint(1.0): nothing cast

}  // namespace

ComputeRasterPass::ComputeRasterPass(gpu::Device& device, const GpuScene& gpuScene) : device_(device), scene_(gpuScene) {
    using gpu::DescriptorType;
    gpu::ComputePipelineDesc desc;
    desc.bindings = sceneBindings();
    desc.bindings.push_back({5, DescriptorType::UniformBuffer});
    for (uint32_t binding = 6; binding <= 13; ++binding) desc.bindings.push_back({binding, DescriptorType::StorageBuffer});
    desc.pushConstantSize = sizeof(glm::uvec4);
    desc.textureTable = gpuScene.textureTable();
    for (auto [pipeline, shader] : {std::pair{&small_, "shadow_raster.comp"}, std::pair{&bin_, "shadow_raster_bin.comp"},
                                    std::pair{&chunks_, "shadow_raster_chunks.comp"}}) {
        desc.shader = shader;
        desc.debugName = shader;
        *pipeline = device.createComputePipeline(desc);
    }
    gpu::ComputePipelineDesc args;
    args.shader = "shadow_raster_args.comp";
    args.bindings = {{9, DescriptorType::StorageBuffer}};
    args.pushConstantSize = sizeof(glm::uvec4);
    args.debugName = "shadow raster dispatch sizes";
    args_ = device.createComputePipeline(args);
    using gpu::MemoryKind;
    counters_ = device.createBuffer(sizeof(gpu_data::RasterCounters), gpu::kBufferStorage | gpu::kBufferIndirect,
                                    MemoryKind::DeviceLocal, nullptr, "shadow raster counters");
    large_ = device.createBuffer(gpu_data::kRasterMaxLarge * sizeof(gpu_data::RasterTriangle), gpu::kBufferStorage,
                                 MemoryKind::DeviceLocal, nullptr, "shadow raster large triangles");
    chunkList_ = device.createBuffer(uint64_t(gpu_data::kRasterMaxChunks) * 8, gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                     nullptr, "shadow raster chunks");
}

ComputeRasterPass::~ComputeRasterPass() {
    for (gpu::PipelineHandle p : {small_, bin_, chunks_, args_}) device_.destroy(p);
    for (gpu::BufferHandle b : {counters_, large_, chunkList_}) device_.destroy(b);
}

void ComputeRasterPass::record(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes,
                               const gpu::BufferSlice& cullFrame, const ShadowCullingPass& culling, uint32_t firstTile,
                               uint32_t tileCount, gpu::TextureHandle atlas, uint32_t atlasSize,
                               gpu::BufferHandle depth) {
    const gpu::BufferSlice depthSlice{depth, 0, uint64_t(atlasSize) * atlasSize * 4};
    // The previous atlas pass (or frame) may still read these buffers.
    commands.memoryBarrier();
    commands.fillBuffer(depth, kFarDepthBits);
    commands.fillBuffer(counters_, 0);
    commands.memoryBarrier();
    if (tileCount > 0) {
        std::vector<gpu::DescriptorWrite> rasterWrites = writes;
        rasterWrites.push_back({5, cullFrame});
        rasterWrites.push_back({6, scene_.cullMeshBuffer(), {}, {}});
        rasterWrites.push_back({7, scene_.indexBuffer(), {}, {}});
        rasterWrites.push_back({8, depthSlice});
        rasterWrites.push_back({9, counters_, {}, {}});
        rasterWrites.push_back({10, large_, {}, {}});
        rasterWrites.push_back({11, chunkList_, {}, {}});
        rasterWrites.push_back({12, culling.listCounts(), {}, {}});
        rasterWrites.push_back({13, culling.visibleInstances(), {}, {}});
        const glm::uvec4 pass(firstTile, tileCount, atlasSize, 0);
        auto bind = [&](gpu::PipelineHandle pipeline) {
            commands.bindPipeline(pipeline);
            commands.pushDescriptors(rasterWrites);
            commands.bindTextureTable(scene_.textureTable());
            commands.pushConstants(&pass, sizeof(pass));
        };
        auto sizeDispatch = [&](uint32_t which) {
            commands.memoryBarrier();
            commands.bindPipeline(args_);
            commands.pushDescriptors(std::vector<gpu::DescriptorWrite>{{9, counters_, {}, {}}});
            const glm::uvec4 selector(which, 0, 0, 0);
            commands.pushConstants(&selector, sizeof(selector));
            commands.dispatch(1, 1);
            commands.memoryBarrier();
        };
        const uint32_t slots = std::max(scene_.instanceCount(), 1u);
        bind(small_);
        commands.dispatch(std::min(slots, gpu_data::kRasterDispatchWidth),
                          (slots + gpu_data::kRasterDispatchWidth - 1) / gpu_data::kRasterDispatchWidth, tileCount);
        sizeDispatch(0);
        bind(bin_);
        commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, largeDispatch));
        sizeDispatch(1);
        bind(chunks_);
        commands.dispatchIndirect(counters_, offsetof(gpu_data::RasterCounters, chunkDispatch));
    }
    commands.memoryBarrier();
    commands.copyBufferToTexture(depth, atlas, gpu::TextureState::ShaderRead);
}

}  // namespace penumbra
