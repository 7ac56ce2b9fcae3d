#pragma once
// Scene lights → the lit pass's LightData array: directional lights first (at most 4), then spot and
// point lights (at most 1024), each carrying its scene index and shadow slot.
#include <string>
#include <vector>

#include "penumbra/scene.h"
#include "scene_structs.h"

namespace penumbra {

struct PackedLights {
    std::vector<gpu_data::LightData> lights;
    uint32_t directionalCount = 0;
    uint32_t otherCount = 0;
    std::vector<std::string> warnings;  // lights beyond the limits, named
};

using gpu_data::kNoShadowSlot;

// shadowSlotOf(sceneLightIndex) gives the light's shadow slot or kNoShadowSlot.
template <typename SlotOf>
PackedLights packLights(const Scene& scene, SlotOf&& shadowSlotOf);

gpu_data::LightData packLight(const Light& light, uint32_t sceneIndex, uint32_t shadowSlot);

template <typename SlotOf>
PackedLights packLights(const Scene& scene, SlotOf&& shadowSlotOf) {
    PackedLights packed;
    std::vector<gpu_data::LightData> others;
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        const bool directional = light.type == LightType::Directional;
        const uint32_t limit = directional ? gpu_data::kMaxDirectionalLights : gpu_data::kMaxOtherLights;
        uint32_t& count = directional ? packed.directionalCount : packed.otherCount;
        if (count >= limit) {
            packed.warnings.push_back("light " + std::to_string(i) + " '" + light.name + "' not drawn: more than " +
                                      std::to_string(limit) + (directional ? " directional" : " spot/point") + " lights");
            continue;
        }
        ++count;
        (directional ? packed.lights : others).push_back(packLight(light, i, shadowSlotOf(i)));
    }
    packed.lights.insert(packed.lights.end(), others.begin(), others.end());
    return packed;
}

}  // namespace penumbra
