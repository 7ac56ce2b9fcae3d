#pragma once
// The camera part of the per-frame block the scene shaders read (scene_structs.h FrameData).
#include "penumbra/camera.h"
#include "scene_structs.h"
#include "shadow_view_structs.h"

namespace penumbra {

// Matrices, camera position and viewport of `view`; counts and params zero (the caller fills them).
inline gpu_data::FrameData cameraFrameData(const CameraView& view) {
    gpu_data::FrameData frame{};
    frame.clipFromWorld = view.clipFromWorld;
    frame.viewFromWorld = view.viewFromWorld;
    frame.worldFromClip = glm::inverse(view.clipFromWorld);
    frame.wsCameraPosition = glm::vec4(view.wsPosition, 1.0f);
    frame.viewport = glm::vec4(float(view.width), float(view.height), 1.0f / float(view.width), 1.0f / float(view.height));
    return frame;
}

// The camera block of the shadow sampling (penumbra/shadows.glsl): `lightCount` entries in its light table.
inline gpu_data::ShadowViewData shadowViewData(const CameraView& view, uint32_t lightCount) {
    gpu_data::ShadowViewData data{};
    data.viewFromWorld = view.viewFromWorld;
    data.wsCameraPosition = glm::vec4(view.wsPosition, 1.0f);
    data.lightCount = lightCount;
    return data;
}

}  // namespace penumbra
