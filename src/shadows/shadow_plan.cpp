// planShadows (penumbra/shadow_plan.h): ShadowPlanner's frame as public plain data.
#include "penumbra/shadow_plan.h"

#include "shadows/shadow_planner.h"

namespace penumbra {

namespace {

PlannedShadowMap plannedMap(const ShadowTile& tile, uint32_t sceneLight) {
    PlannedShadowMap map;
    map.sceneLight = sceneLight;
    map.cascade = tile.cascadeIndex;
    map.atlasX = tile.rect.offset.x;
    map.atlasY = tile.rect.offset.y;
    map.size = tile.rect.size;
    map.scissorInset = tile.scissorInset;
    map.lightFromWorld = tile.lightFromWorld;
    map.clipFromWorld = tile.clipFromWorld;
    map.atlasFromWorld = tile.atlasFromWorld;
    map.wsTexelSize = tile.wsTexelSize;
    map.perspective = tile.perspective;
    map.depthClamp = tile.depthClamp;
    map.casterInstances = tile.casterInstances;
    return map;
}

}  // namespace

ShadowPlan planShadows(const Scene& scene, const CameraView& view, const ShadowSettings& settings) {
    validateShadowSettings(settings);
    ShadowSettings sphere = settings;
    sphere.directional.fit = CascadeFit::Sphere;  // no view depth to fit to (shadow_plan.h)
    const ShadowFrame frame = ShadowPlanner::plan(scene, view, sphere);
    ShadowPlan plan;
    const DirectionalShadowPlan& directional = frame.directional;
    plan.directionalAtlasSize = directional.atlas.tileCount > 0 ? directional.atlas.atlasSize : 0u;
    for (const CascadeSphere& cascade : directional.cascades)
        plan.cascades.push_back({cascade.vsNear, cascade.vsFar, cascade.wsCenter, cascade.radius});
    for (const ShadowTile& tile : directional.tiles)
        plan.directionalMaps.push_back(plannedMap(tile, directional.lights.at(tile.lightSlot).sceneLightIndex));
    const OtherShadowPlan& other = frame.other;
    plan.otherAtlasSize = other.atlas.tileCount > 0 ? other.atlas.atlasSize : 0u;
    for (const ShadowTile& tile : other.tiles)
        plan.otherMaps.push_back(plannedMap(tile, other.lights.at(tile.lightSlot).sceneLightIndex));
    plan.droppedLights = other.droppedLights;
    plan.warnings = other.warnings;
    return plan;
}

}  // namespace penumbra
