#pragma once
// Clustered light culling on the GPU (light_cluster_structs.h): each frame one
// compute pass gives every froxel of the view the mask of the spot and point lights that can light
// it; the lit pass loops over its cluster's lights only. render/light_clusters.h is the CPU reference.
#include <vector>

#include "gpu/device.h"

namespace penumbra {

class LightClusterPass {
public:
    explicit LightClusterPass(gpu::Device& device);
    ~LightClusterPass();
    LightClusterPass(const LightClusterPass&) = delete;
    LightClusterPass& operator=(const LightClusterPass&) = delete;

    // Writes the masks for `clusters` (a LightClusterData in this frame's upload ring) from `lights`
    // (the frame's LightData array). Nothing is dispatched when clusters.clustered is 0.
    void record(gpu::CommandList& commands, const gpu::BufferSlice& clusters, const gpu::BufferSlice& lights,
                bool clustered);
    gpu::BufferHandle masks() const { return masks_; }
    // LightClusterStats of the last recorded pass, GPU-written; read back with Device::readBackAtFrameEnd.
    gpu::BufferSlice stats() const;
    // Tests (waits for the GPU): the mask words of the last recorded pass, `words` per cluster.
    std::vector<uint32_t> readMasks(uint32_t words);

private:
    void create();
    void destroyAll();

    gpu::Device& device_;
    gpu::PipelineHandle pipeline_;
    gpu::BufferHandle masks_, stats_;
};

}  // namespace penumbra
