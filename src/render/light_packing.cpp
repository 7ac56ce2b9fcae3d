#include "render/light_packing.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

gpu_data::LightData packLight(const Light& light, uint32_t sceneIndex, uint32_t shadowSlot) {
    gpu_data::LightData data{};
    uint32_t type = gpu_data::kLightDirectional;
    if (light.type == LightType::Spot) type = gpu_data::kLightSpot;
    if (light.type == LightType::Point) type = gpu_data::kLightPoint;
    data.color = light.color * light.intensity;
    data.type = type;
    data.invRangeSquared = light.range > 0.0f ? 1.0f / (light.range * light.range) : 0.0f;
    data.wsPosition = light.wsPosition;
    data.wsToLight = -glm::normalize(light.wsDirection);
    // KHR_lights_punctual's recommended cone falloff: scale and offset on cos(angle).
    const float cosOuter = std::cos(light.outerConeAngle);
    const float cosInner = std::cos(std::min(light.innerConeAngle, light.outerConeAngle - 1e-4f));
    const float scale = 1.0f / std::max(1e-4f, cosInner - cosOuter);
    data.spotScale = scale;
    data.spotOffset = -cosOuter * scale;
    data.sceneLightIndex = sceneIndex;
    data.shadowSlot = shadowSlot;
    return data;
}

}  // namespace penumbra
