#pragma once
// Clustered light culling on the CPU: the cluster block of a frame, the froxels'
// view-space boxes and the conservative light test. The GPU pass (light_cluster_pass.h, shaders/
// light_cluster.comp.glsl) does the same per frame; this is its reference, used by the tests.
// Layout and conventions: shaders/shared/light_cluster_structs.h.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "light_cluster_structs.h"
#include "penumbra/camera.h"
#include "penumbra/scene.h"
#include "scene_structs.h"

namespace penumbra {

// The far end of the slices: the camera's far plane when finite, else the farthest view depth of the
// scene's bounds (at least twice the near plane).
float clusterFarDepth(const CameraView& view, const Aabb& wsSceneBounds);

// The frame's cluster block. `firstOther` is the LightData index of the first spot / point light.
gpu_data::LightClusterData makeLightClusterData(const CameraView& view, const Aabb& wsSceneBounds, uint32_t firstOther,
                                                uint32_t otherCount, bool clustered);

struct ViewBox {
    glm::vec3 vsMin{0.0f}, vsMax{0.0f};
};

// The view-space box around cluster (tileX, tileY, slice), grown by kClusterBoundsMargin.
ViewBox clusterViewBox(const gpu_data::LightClusterData& clusters, uint32_t tileX, uint32_t tileY, uint32_t slice);

// False only when the spot / point light adds nothing to any point of the box: outside its range
// sphere, or (a spot) outside its outer cone.
bool lightTouchesViewBox(const gpu_data::LightData& light, const glm::mat4& viewFromWorld, const ViewBox& box);

// The cluster of a pixel (its centre in pixels) at view depth vsDepth, or -1 beyond the last slice.
int32_t clusterOfPixel(const gpu_data::LightClusterData& clusters, const glm::vec2& pixel, float vsDepth);

// Every cluster's mask words (wordsPerCluster per cluster); `lights` is the frame's whole LightData array.
std::vector<uint32_t> clusterLightMasks(const gpu_data::LightClusterData& clusters,
                                        const std::vector<gpu_data::LightData>& lights);

}  // namespace penumbra
