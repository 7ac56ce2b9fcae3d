#include "shadows/shadow_planner.h"

#include <algorithm>

#include "core/reuse.h"
#include "core/stopwatch.h"
#include "shadows/caster_culling.h"
#include "shadows/shadow_gpu_packing.h"
#include "shadows/spot_shadow_planner.h"

namespace penumbra {

namespace {

struct TileInputs {
    const Scene& scene;
    const std::vector<uint32_t>& casters;
    const std::vector<Aabb>& rsBounds;  // casters' bounds in the light's rotation-only space
    const std::vector<CascadeSphere>& spheres;
    const AtlasLayout& atlas;
    BlendCulling blendCulling;
    ShadowFilter filter;
    const VisibleSurfaces* visible;  // the tight fit's receivers; null = the sphere fit
    float cascadeFade;
    bool cullCasters;
    const ReceiverVolume& cameraReceivers;  // invalid: receiver culling off
    const Aabb& wsReceivers;                // the receivers' common bounds
};

// How far toward the light the lit pass may look up a receiver of this cascade: the normal bias moves
// the lookup by up to normalBias units (shadow_gpu_packing.h), plus one texel of rounding.
float nearPlaneMargin(const ReservedDirectionalLight& light, float wsTexelSize, ShadowFilter filter) {
    return wsTexelSize * (1.0f + light.normalBias * gpu_data::normalOffsetFootprint(uint32_t(filter)));
}


// The cascade's light view: around its culling sphere, or (tight fit) around the visible points of its
// slice, which reaches back over the previous cascade's blend band (those points sample it too).
CascadeLightView fitLightView(const TileInputs& in, const ReservedDirectionalLight& light,
                              const glm::mat4& lightRotation, uint32_t cascadeIndex) {
    const CascadeSphere& sphere = in.spheres[cascadeIndex];
    if (!in.visible) return fitCascadeLightView(lightRotation, sphere, in.atlas.tileSize);
    const float vsNear = cascadeIndex == 0 ? 0.0f : sphere.vsNear * (1.0f - in.cascadeFade);
    Aabb rsBounds = rotatedVisibleBounds(*in.visible, lightRotation, vsNear, sphere.vsFar);
    if (!rsBounds.valid()) {  // nothing visible in this slice: a minimal tile that nothing samples
        const glm::vec3 rsCenter = glm::vec3(lightRotation * glm::vec4(sphere.wsCenter, 1.0f));
        rsBounds = Aabb{rsCenter - 1e-3f, rsCenter + 1e-3f};
    }
    const float reachTexels = lookupReachTexels(light.normalBias, light.pcssTanRadius > 0.0f, in.filter);
    return fitTightLightView(lightRotation, rsBounds, in.atlas.tileSize, reachTexels);
}

// Where the receivers that sample cascade `cascadeIndex` lie: the camera's frustum narrowed to the slice's
// view depth, reaching back over the previous cascade's blend band (tight fit: cascades selected by depth,
// as selectDirectionalCascade), or to its culling sphere (sphere fit: cascades selected by sphere).
ReceiverVolume cascadeReceiverVolume(const TileInputs& in, uint32_t cascadeIndex) {
    ReceiverVolume volume = in.cameraReceivers;
    const CascadeSphere& sphere = in.spheres[cascadeIndex];
    if (!volume.valid) return volume;
    if (in.visible) volume.vsDepthRange = {cascadeIndex == 0 ? -kAnyDepth : sphere.vsNear * (1.0f - in.cascadeFade), sphere.vsFar};
    else volume.wsSphere = glm::vec4(sphere.wsCenter, sphere.radius);
    return volume;
}

ShadowTile planTile(const TileInputs& in, const ReservedDirectionalLight& light, const glm::mat4& lightRotation,
                    uint32_t slot, uint32_t cascadeIndex, ShadowStats& stats) {
    const CascadeLightView view = fitLightView(in, light, lightRotation, cascadeIndex);
    const ReceiverVolume receivers = cascadeReceiverVolume(in, cascadeIndex);
    const float wsReach = view.wsTexelSize * lookupReachTexels(light.normalBias, light.pcssTanRadius > 0.0f, in.filter);
    const Stopwatch cullingTime;
    TileCasters casters;
    if (in.cullCasters)
        casters = cullTileCasters(in.scene, in.casters, in.rsBounds, view, in.spheres, cascadeIndex, in.blendCulling,
                                  ReceiverCulling{&receivers, &in.wsReceivers, wsReach});
    stats.cullingMilliseconds += cullingTime.milliseconds();
    stats.skippedByReceiverCulling += casters.skippedByReceiverCulling;
    stats.skippedByBlendCulling += casters.skippedByBlendCulling;

    ShadowTile tile;
    tile.lightSlot = slot;
    tile.cascadeIndex = cascadeIndex;
    const uint32_t tileIndex = light.firstTile + cascadeIndex;
    tile.rect = tileRect(in.atlas, tileIndex);
    tile.lightFromWorld = view.lightFromWorld;
    tile.lsHalfExtent = view.halfExtent;
    tile.wsTexelSize = view.wsTexelSize;
    tile.receiverVolume = receivers;
    tile.wsReceiverReach = wsReach;
    // The depth range fits the receivers, whatever the casters: from the sphere's (or the
    // tight box's) side toward the light, plus what the normal bias may add, to its far side; nothing
    // outside it is sampled. Casters in front of the near plane are pancaked onto it by depth clamp, per
    // fragment (no clipping, no distortion of triangles that cross the plane); shadowNearPlane pulls
    // the near plane back.
    tile.farDistance = view.receiversFar;
    tile.nearDistance = view.receiversNear + nearPlaneMargin(light, view.wsTexelSize, in.filter) + light.nearPlaneOffset;
    tile.pancakedDepth = std::max(0.0f, casters.lsMaxZ - tile.nearDistance);
    tile.clipFromLight = orthoClipFromLight(view.halfExtent, tile.nearDistance, tile.farDistance);
    tile.clipFromWorld = tile.clipFromLight * tile.lightFromWorld;
    tile.atlasFromWorld = atlasFromClip(in.atlas, tileIndex) * tile.clipFromWorld;
    tile.slopeScaleBias = 0.0f;  // the light's shadowBias is applied by the lit pass (penumbra/shadows/bias.glsl)
    tile.depthClamp = true;
    tile.casterInstances = std::move(casters.instances);
    return tile;
}

}  // namespace

namespace {

// The directional plan's lights, cascades and tiles (the spot and point lights are planOtherShadows').
void planDirectional(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                     const VisibleSurfaces* visible, const PlanOptions& options, ShadowFrame& frame,
                     ShadowPlanWorkspace& workspace) {
    DirectionalShadowPlan& directional = frame.directional;
    const DirectionalShadowSettings& config = settings.directional;
    // The tight fit needs the frame's visible surfaces; without them (or with none) it is the sphere fit.
    const bool tight = config.fit == CascadeFit::Tight && visible && !visible->empty();
    directional.tight = tight;
    // The last split just beyond the farthest visible point (cascades select by depth < split).
    computeCascadeSpheres(camera, settings, tight ? visible->vsMinDepth : camera.zNear,
                          tight ? visible->vsMaxDepth * 1.001f + 1e-3f : shadowDistance(camera, settings.maxDistance),
                          directional.cascades);
    const std::vector<uint32_t>& casters = workspace.casters;
    reserveDirectionalShadows(scene, directional.cascades, casters, config.cascadeCount, directional.lights);
    directional.slotOfSceneLight.assign(scene.lights.size(), -1);
    // Virtual shadow maps (render/virtual_shadows.h) shadow the reserved lights without cascade tiles.
    const bool virtualMaps = config.mode == DirectionalShadowMode::Virtual;
    const uint32_t tilesPerLight = virtualMaps ? 0u : config.cascadeCount;
    directional.atlas = makeAtlasLayout(config.atlasSize, uint32_t(directional.lights.size()) * tilesPerLight);

    // Blend culling asks where a caster's shadow can land: anywhere in the receivers' common bounds (one
    // box, so the same rule costs O(1) per caster on the CPU and in the GPU culling pass). It reasons
    // about culling spheres; the tight fit selects cascades by view depth, so it draws every caster that
    // meets a cascade's box.
    directional.wsReceiverBounds = workspace.wsReceiverBounds;
    directional.blendCullingFactor = tight ? 0.0f : cascadeBlendCullingFactor(config.cascadeFade);
    workspace.receivers.assign(1, directional.wsReceiverBounds);
    workspace.cameraReceivers = config.receiverCulling && directional.wsReceiverBounds.valid() ? cameraReceiverVolume(camera)
                                                                                               : ReceiverVolume{};
    const BlendCulling blendCulling{directional.blendCullingFactor,
                                    directional.wsReceiverBounds.valid() ? &workspace.receivers : nullptr};
    directional.specializationMode = 0;
    directional.specializationFilter = gpu_data::kShadowFilterPcf5x5;  // any: no light reads it
    for (uint32_t slot = 0; slot < directional.lights.size(); ++slot) {
        const ReservedDirectionalLight& light = directional.lights[slot];
        directional.slotOfSceneLight[light.sceneLightIndex] = int32_t(slot);
        directional.specializationMode |= virtualMaps ? gpu_data::kDirectionalShadowsVirtual : gpu_data::kDirectionalShadowsCascades;
        if (light.pcssTanRadius > 0.0f) directional.specializationMode |= gpu_data::kDirectionalShadowsPcss;
        // The packed light's filterMode (shadow_gpu_packing.cpp): soft lights the setting's, hard ones PCF2x2.
        const uint32_t filter = light.soft ? uint32_t(config.filter) : gpu_data::kShadowFilterPcf2x2;
        directional.specializationFilter = slot == 0 || filter == directional.specializationFilter ? filter
                                                                                                   : gpu_data::kShadowFilterFromData;
        const glm::mat4 rotation = lightRotationFromWorld(light.wsDirection);
        workspace.rsCasterBounds.clear();
        if (options.cullCasters) workspace.rsCasterBounds = rotatedCasterBounds(scene, casters, rotation);
        const TileInputs inputs{scene,         casters, workspace.rsCasterBounds, directional.cascades, directional.atlas,
                                blendCulling,  config.filter, tight ? visible : nullptr, config.cascadeFade,
                                options.cullCasters, workspace.cameraReceivers, directional.wsReceiverBounds};
        for (uint32_t cascade = 0; cascade < tilesPerLight; ++cascade)
            directional.tiles.push_back(planTile(inputs, light, rotation, slot, cascade, frame.stats));
    }
}

}  // namespace

void ShadowPlanWorkspace::instanceMoved(const Scene& scene, uint32_t instance, const Aabb& wsOldBounds) {
    ++casterEpoch;  // a caster's bounds changed: the lights' reservations look again (their witnesses first)
    if (sceneVersion == 0) return;  // the next plan walks anyway
    const Instance& moved = scene.instances.at(instance);
    const Aabb& wsNewBounds = moved.wsBounds;
    if (wsOldBounds.valid() != wsNewBounds.valid()) {  // it joins or leaves the casters and receivers
        sceneVersion = 0;
        return;
    }
    if (!wsNewBounds.valid() || !isShadowReceiver(scene, moved)) return;
    for (int axis = 0; axis < 3; ++axis) {
        const bool leftMin = wsOldBounds.min[axis] <= wsReceiverBounds.min[axis] && wsNewBounds.min[axis] > wsReceiverBounds.min[axis];
        const bool leftMax = wsOldBounds.max[axis] >= wsReceiverBounds.max[axis] && wsNewBounds.max[axis] < wsReceiverBounds.max[axis];
        if (leftMin || leftMax) {  // the union may shrink: only a walk knows by how much
            sceneVersion = 0;
            return;
        }
    }
    wsReceiverBounds.extend(wsNewBounds);
}

void ShadowPlanner::plan(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                         const VisibleSurfaces* visible, const PlanOptions& options, ShadowFrame& frame,
                         ShadowPlanWorkspace& workspace) {
    resetKeepingStorage(frame.directional, &DirectionalShadowPlan::lights, &DirectionalShadowPlan::cascades,
                        &DirectionalShadowPlan::tiles, &DirectionalShadowPlan::slotOfSceneLight);
    resetKeepingStorage(frame.stats, &ShadowStats::castersPerTile);
    if (options.sceneVersion == 0 || options.sceneVersion != workspace.sceneVersion) {  // else still valid
        shadowCasterInstances(scene, workspace.casters);
        workspace.wsReceiverBounds = shadowReceiverUnion(scene);
        workspace.sceneVersion = options.sceneVersion;
        ++workspace.casterEpoch;
    }
    planDirectional(scene, camera, settings, visible, options, frame, workspace);

    ShadowStats& stats = frame.stats;
    const DirectionalShadowPlan& directional = frame.directional;
    for (const Light& light : scene.lights) stats.directionalLightsConsidered += light.type == LightType::Directional;
    stats.directionalLightsReserved = uint32_t(directional.lights.size());
    stats.shadowCasters = uint32_t(workspace.casters.size());
    for (const ShadowTile& tile : directional.tiles) {
        stats.castersPerTile.push_back(uint32_t(tile.casterInstances.size()));
        stats.casterDraws += uint32_t(tile.casterInstances.size());
    }
    const float distance = shadowDistance(camera, settings.maxDistance);
    frame.directional.gpu = packDirectionalShadowData(directional, settings, distance);
    // Without a scene version nothing says whether the casters changed: every light's answer is found again.
    planOtherShadows(scene, camera, settings, workspace.casters, distance, options.cullCasters, frame.other,
                     workspace.reservation, options.sceneVersion == 0 ? 0 : workspace.casterEpoch);
    stats.cullingMilliseconds += frame.other.cullingMilliseconds;
}

ShadowFrame ShadowPlanner::plan(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                                const VisibleSurfaces* visible, const PlanOptions& options) {
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    plan(scene, camera, settings, visible, options, frame, workspace);
    return frame;
}

}  // namespace penumbra
