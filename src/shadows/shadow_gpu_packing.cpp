#include "shadows/shadow_gpu_packing.h"

#include <algorithm>

#include "core/error.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// The shadow data carries these enums as integers (shadow_structs.h); spot_shadow_planner.cpp packs
// the same ones for the other atlas.
static_assert(uint32_t(ShadowFilter::PCF2x2) == gpu_data::kShadowFilterPcf2x2 &&
              uint32_t(ShadowFilter::PCF3x3) == gpu_data::kShadowFilterPcf3x3 &&
              uint32_t(ShadowFilter::PCF5x5) == gpu_data::kShadowFilterPcf5x5 &&
              uint32_t(ShadowFilter::PCF7x7) == gpu_data::kShadowFilterPcf7x7);
static_assert(uint32_t(CascadeBlend::Hard) == gpu_data::kCascadeBlendHard &&
              uint32_t(CascadeBlend::Soft) == gpu_data::kCascadeBlendSoft &&
              uint32_t(CascadeBlend::Dither) == gpu_data::kCascadeBlendDither);
static_assert(uint32_t(ShadowBiasMode::Normal) == gpu_data::kShadowBiasNormal &&
              uint32_t(ShadowBiasMode::ScaledNormal) == gpu_data::kShadowBiasScaledNormal &&
              uint32_t(ShadowBiasMode::ReceiverPlane) == gpu_data::kShadowBiasReceiverPlane);
static_assert(uint32_t(ShadowFadeMode::Linear) == gpu_data::kShadowFadeLinear &&
              uint32_t(ShadowFadeMode::Squared) == gpu_data::kShadowFadeSquared);

// Catlike Coding "Directional Shadows" (PCF Filtering) scales the normal bias with the filter's whole
// footprint, filter + 1 texels. Measured on lavapipe (tests/scenes/compare_table.sh; a 60° plane with no
// slope bias, any darkening counted as acne), acne needs a unit of only about 1.0 / 1.1 / 1.6 / 2.1 texels
// for PCF2x2 / 3x3 / 5x5 / 7x7: the tent's outer ring carries little weight, so each wider filter needs about
// half a texel more, not a whole one. 1 + filterSize / 2 keeps a 0.4-texel margin there (no acne on planes at
// 45-85° either) and cuts the over-bias of the wide filters: on the canonical scenes PCF7x7 misclassified
// 2.25 -> 1.47 % and interior 0.28 -> 0.00 % on thin_wall, near_far_casters 2.05 -> 1.27 % / 0.49 -> 0.22 %.
// sqrt(1 + filterSize) (2 for PCF7x7) left faint acne on the 60° plane; one texel for all filters, much. The
// rule is gpu_data::normalOffsetFootprint (shadow_structs.h), shared with the shaders and with spot and point
// lights (which used 1 + filter before).

gpu_data::DirectionalCascade packCascade(const CascadeSphere& sphere, uint32_t tileSize, ShadowFilter filter) {
    const float texelSize = 2.0f * sphere.radius / float(tileSize);
    const float filterWorldSize = texelSize * (filterSize(filter) + 1.0f);
    // The tutorial subtracts without a floor; a floor keeps 1 / r^2 finite for degenerate tiny cascades.
    const float radius = std::max(sphere.radius - filterWorldSize, 1e-6f);
    const float radiusSqr = radius * radius;
    gpu_data::DirectionalCascade cascade{};
    cascade.cullingSphere = glm::vec4(sphere.wsCenter, radiusSqr);
    cascade.invRadiusSquared = 1.0f / radiusSqr;
    cascade.normalBiasUnit = texelSize * gpu_data::normalOffsetFootprint(uint32_t(filter));
    cascade.wsTexelSize = texelSize;
    cascade.vsSplit = sphere.vsFar;
    return cascade;
}

gpu_data::DirectionalShadowData packDirectionalShadowData(const DirectionalShadowPlan& plan,
                                                          const ShadowSettings& settings, float shadowDistance) {
    gpu_data::DirectionalShadowData data{};  // zero: unused tiles, cascades and slots stay zero
    const DirectionalShadowSettings& directional = settings.directional;
    PENUMBRA_ASSERT(plan.tiles.size() <= gpu_data::kMaxDirectionalShadowTiles);
    for (size_t i = 0; i < plan.tiles.size(); ++i) data.atlasFromWorld[i] = plan.tiles[i].atlasFromWorld;
    const uint32_t tileSize = std::max(plan.atlas.tileSize, 1u);
    for (size_t i = 0; i < plan.cascades.size() && i < gpu_data::kMaxCascades; ++i) {
        data.cascades[i] = packCascade(plan.cascades[i], tileSize, directional.filter);
    }
    for (size_t i = 0; i < plan.lights.size(); ++i) {
        const ReservedDirectionalLight& light = plan.lights[i];
        gpu_data::DirectionalShadowLight& packed = data.lights[i];
        packed.strength = light.strength;
        packed.firstTile = light.firstTile;
        packed.normalBias = light.normalBias;
        packed.sceneLightIndex = light.sceneLightIndex;
        packed.slopeBias = light.slopeScaleBias;
        const ShadowFilter filter = light.soft ? directional.filter : ShadowFilter::PCF2x2;  // URP's soft flag
        packed.filterMode = uint32_t(filter);
        packed.pcssTanRadius = light.pcssTanRadius;
        packed.wsToLight = glm::vec4(-light.wsDirection, 0.0f);
    }
    data.biasMode = uint32_t(settings.bias);
    data.fadeMode = uint32_t(settings.fadeMode);
    data.cascadeFit = plan.tight ? gpu_data::kCascadeFitTight : gpu_data::kCascadeFitSphere;
    const glm::vec2 squaredFade = squaredFadeScaleBias(shadowDistance, settings.distanceFade);
    data.invCascadeFade = 1.0f / directional.cascadeFade;
    data.squaredFadeScale = squaredFade.x;
    data.squaredFadeBias = squaredFade.y;
    const float fade = directional.cascadeFade;
    data.invShadowDistance = 1.0f / shadowDistance;
    data.invDistanceFade = 1.0f / settings.distanceFade;
    data.cascadeFadeScale = 1.0f / (1.0f - (1.0f - fade) * (1.0f - fade));
    data.shadowDistance = shadowDistance;
    data.cascadeCount = directional.cascadeCount;
    data.filterMode = uint32_t(directional.filter);
    data.cascadeBlend = uint32_t(directional.cascadeBlend);
    data.lightCount = uint32_t(plan.lights.size());
    const float atlasSize = float(std::max(plan.atlas.atlasSize, 1u));
    data.atlasSize = atlasSize;
    data.invAtlasSize = 1.0f / atlasSize;
    data.tileSize = float(tileSize);
    data.invTileSize = 1.0f / float(tileSize);
    return data;
}

float lookupReachTexels(float normalBias, bool pcss, ShadowFilter filter) {
    const float taps = pcss ? gpu_data::kPcssMaxRadiusTexels : filterSize(filter);
    return taps + 2.0f + normalBias * gpu_data::normalOffsetFootprint(uint32_t(filter));
}

}  // namespace penumbra
