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

// shadowSlotOf(sceneLightIndex) gives the light's shadow slot or kNoShadowSlot. Packs into `packed`
// (replaced; its storage reused).
template <typename SlotOf>
void packLights(const Scene& scene, SlotOf&& shadowSlotOf, PackedLights& packed);
template <typename SlotOf>
PackedLights packLights(const Scene& scene, SlotOf&& shadowSlotOf) {
    PackedLights packed;
    packLights(scene, shadowSlotOf, packed);
    return packed;
}

gpu_data::LightData packLight(const Light& light, uint32_t sceneIndex, uint32_t shadowSlot);

template <typename SlotOf>
void packLights(const Scene& scene, SlotOf&& shadowSlotOf, PackedLights& packed) {
    packed.lights.clear();
    packed.warnings.clear();
    packed.directionalCount = packed.otherCount = 0;
    // Directional lights first, then the spot and point lights, each in scene order up to its limit.
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
        if (directional) packed.lights.push_back(packLight(light, i, shadowSlotOf(i)));
    }
    uint32_t others = 0;
    for (uint32_t i = 0; i < scene.lights.size() && others < packed.otherCount; ++i) {
        if (scene.lights[i].type == LightType::Directional) continue;
        packed.lights.push_back(packLight(scene.lights[i], i, shadowSlotOf(i)));
        ++others;
    }
}

}  // namespace penumbra
