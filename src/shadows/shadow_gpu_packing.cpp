#include "shadows/shadow_gpu_packing.h"

#include <algorithm>

#include "core/error.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

void packCascade(const CascadeSphere& sphere, uint32_t tileSize, ShadowFilter filter, glm::vec4& cullingSphere,
                 glm::vec4& cascadeData) {
    const float texelSize = 2.0f * sphere.radius / float(tileSize);
    const float filterWorldSize = texelSize * (filterSize(filter) + 1.0f);
    // The seed subtracts without a floor; a floor keeps 1 / r^2 finite for degenerate tiny cascades.
    const float radius = std::max(sphere.radius - filterWorldSize, 1e-6f);
    const float radiusSqr = radius * radius;
    cullingSphere = glm::vec4(sphere.wsCenter, radiusSqr);
    cascadeData = glm::vec4(1.0f / radiusSqr, filterWorldSize * 1.4142136f, texelSize, 0.0f);
}

gpu_data::DirectionalShadowData packDirectionalShadowData(const DirectionalShadowPlan& plan,
                                                          const ShadowSettings& settings, float shadowDistance) {
    gpu_data::DirectionalShadowData data{};  // zero: unused tiles, cascades and slots stay zero
    const DirectionalShadowSettings& directional = settings.directional;
    PENUMBRA_ASSERT(plan.tiles.size() <= gpu_data::kMaxDirectionalShadowTiles);
    for (size_t i = 0; i < plan.tiles.size(); ++i) data.atlasFromWorld[i] = plan.tiles[i].atlasFromWorld;
    const uint32_t tileSize = std::max(plan.atlas.tileSize, 1u);
    for (size_t i = 0; i < plan.cascades.size() && i < gpu_data::kMaxCascades; ++i) {
        packCascade(plan.cascades[i], tileSize, directional.filter, data.cullingSpheres[i], data.cascadeData[i]);
    }
    for (size_t i = 0; i < plan.lights.size(); ++i) {
        const ReservedDirectionalLight& light = plan.lights[i];
        data.lights[i] = glm::vec4(light.strength, float(light.firstTile), light.normalBias, float(light.sceneLightIndex));
    }
    const float fade = directional.cascadeFade;
    data.fade = glm::vec4(1.0f / shadowDistance, 1.0f / settings.distanceFade,
                          1.0f / (1.0f - (1.0f - fade) * (1.0f - fade)), shadowDistance);
    data.config = glm::uvec4(directional.cascadeCount, uint32_t(directional.filter),
                             uint32_t(directional.cascadeBlend), uint32_t(plan.lights.size()));
    const float atlasSize = float(std::max(plan.atlas.atlasSize, 1u));
    data.atlasSize = glm::vec4(atlasSize, 1.0f / atlasSize, float(tileSize), 1.0f / float(tileSize));
    return data;
}

}  // namespace penumbra
