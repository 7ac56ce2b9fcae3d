#pragma once
// The spot and point lights' virtual page marking on the GPU (shaders/virtual_face_mark.comp.glsl): from
// the main view's depth, the request bit of every face page (shadows/virtual_faces.h) that the view's
// shadow lookups will read. shadows/virtual_faces.h markVirtualFacePages is the CPU reference and defines
// the rules and the bit layout (virtualPageBit of level mip * faceCount + face). The depth comes from a
// D32 texture or the visibility buffer (render/virtual_page_mark_pass.h VirtualPageDepthSource).
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/device.h"
#include "render/virtual_page_mark_pass.h"
#include "shadows/virtual_faces.h"
#include "virtual_face_structs.h"

namespace penumbra {

// The uniform data of one marking of faceCount faces of lightCount lights.
gpu_data::VirtualFaceMarkData packVirtualFaceMark(const VirtualFaceConfig& config, const CameraView& view,
                                                  uint32_t faceCount, uint32_t lightCount, float marginTexels,
                                                  float footprintScale);
gpu_data::VirtualFaceData packVirtualFace(const VirtualFace& face);

// Where a marking's inputs are: its uniform data and the faces' and lights' records (storage).
struct VirtualFaceMarkInputs {
    gpu::BufferSlice mark;    // VirtualFaceMarkData
    gpu::BufferSlice faces;   // faceCount VirtualFaceData
    gpu::BufferSlice lights;  // lightCount VirtualFaceLightData
};

class VirtualFaceMarkPass {
public:
    explicit VirtualFaceMarkPass(gpu::Device& device);
    ~VirtualFaceMarkPass();
    VirtualFaceMarkPass(const VirtualFaceMarkPass&) = delete;
    VirtualFaceMarkPass& operator=(const VirtualFaceMarkPass&) = delete;

    // Clears the request bits of a table of `layout` and marks them from `source`.
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& source, const VirtualFaceMarkInputs& inputs,
                const VirtualPageTableLayout& layout);
    gpu::BufferSlice requestWords() const { return {requests_, 0, requestBytes_}; }

    // Tests and debugging: marks from a CPU depth image (as visibleSurfacesFromDepth reads it) and waits
    // for the request bits.
    std::vector<uint32_t> markNow(const Image& depth, const CameraView& view, const VirtualFaceConfig& config,
                                  std::span<const VirtualFace> faces, std::span<const VirtualFaceLight> lights,
                                  float marginTexels, float footprintScale);

private:
    void ensureRequests(const VirtualPageTableLayout& layout);

    gpu::Device& device_;
    DepthSourcePipelines pipelines_;
    gpu::BufferHandle requests_;
    uint64_t requestBytes_ = 0;
};

}  // namespace penumbra
