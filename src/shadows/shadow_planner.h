#pragma once
// The shadow plan of one frame: Scene + CameraView + ShadowSettings -> ShadowFrame, pure CPU. The renderer
// only executes it: one depth pass per tile, then the lit pass reads the packed DirectionalShadowData.
//
// Depth convention of every shadow tile (see shaders/shared/shadow_structs.h):
// - clip space is Vulkan's: x right, y down in NDC, z in [0, 1]; orthographic (w = 1);
// - STANDARD depth: 0 at the near plane (toward the light), 1 at the far plane. Clear the atlas to 1,
//   draw casters with depth test LESS, sample with compare op LESS_OR_EQUAL (fragment <= stored -> lit);
// - shadow pancaking (Catlike Coding "Directional Shadows", Shadow Pancaking): tiles with depthClamp set
//   must be drawn with depthClampEnable so casters in front of the near plane flatten onto it instead of
//   being clipped;
// - no rasterizer depth bias: the caster pass writes the casters' exact depth (clamped to [0, 1] by
//   depth clamp). Every bias, the light's slope-scale shadowBias included, is applied by the lit pass
//   to the receiver (penumbra/shadows/bias.glsl), so a compute rasterizer has only the depth to reproduce.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/scene.h"
#include "other_shadow_structs.h"
#include "shadow_structs.h"
#include "shadows/atlas_layout.h"
#include "shadows/cascades.h"
#include "shadows/caster_culling.h"
#include "shadows/light_reservation.h"
#include "penumbra/shadow_settings.h"
#include "shadows/spot_atlas_layout.h"
#include "shadows/spot_reservation.h"
#include "shadows/virtual_faces.h"
#include "shadows/visible_surfaces.h"

namespace penumbra {

// One shadow map inside an atlas: what one depth pass renders.
struct ShadowTile {
    uint32_t lightSlot = 0;     // index into ShadowFrame::directionalLights
    uint32_t cascadeIndex = 0;  // index into ShadowFrame::cascades; a point light's cube face (other atlas)
    AtlasTileRect rect;         // viewport, in atlas pixels (top-left origin)
    uint32_t scissorInset = 0;  // the scissor is rect shrunk by this many texels per side
    glm::mat4 lightFromWorld{1.0f};
    glm::mat4 clipFromLight{1.0f};
    glm::mat4 clipFromWorld{1.0f};   // what the caster pass's vertex shader uses
    glm::mat4 atlasFromWorld{1.0f};  // world -> (atlas u, v, depth); also packed for the lit pass
    float wsTexelSize = 0.0f;        // world size of one texel of this tile (perspective: at distance 1)
    float nearDistance = 0.0f;       // light-view distance from the sphere centre to the near plane
    float farDistance = 0.0f;        // ... and to the far plane (the sphere radius)
    // Directional tiles: how far the kept casters reach in front of the near plane (pancaked onto it by
    // depth clamp); the depth range would have to grow by this much to hold them all.
    float pancakedDepth = 0.0f;
    float slopeScaleBias = 0.0f;     // depthBiasSlopeFactor: 0 (biases are the lit pass's, see above)
    bool depthClamp = true;          // pancaking: draw with depthClampEnable
    bool perspective = false;        // spot / point face (else a directional cascade)
    float lsHalfExtent = 0.0f;       // directional: the ortho box is [-h, h]^2 in light view
    // Directional: where the receivers that sample this cascade lie (invalid: receiver culling off) and
    // how far from a receiver its lookups reach (world units); the GPU culling pass tests the same.
    ReceiverVolume receiverVolume;
    float wsReceiverReach = 0.0f;
    glm::vec3 wsApex{0.0f};          // perspective: the light's position
    // Indices into Scene::instances, scene order; empty when the plan leaves culling to the GPU
    // (PlanOptions::cullCasters false).
    std::vector<uint32_t> casterInstances;
};

struct ShadowStats {
    uint32_t directionalLightsConsidered = 0;  // directional lights in the scene
    uint32_t directionalLightsReserved = 0;
    uint32_t shadowCasters = 0;              // instances that may cast at all
    std::vector<uint32_t> castersPerTile;    // = tiles[i].casterInstances.size()
    uint32_t casterDraws = 0;                // sum over tiles
    uint32_t skippedByBlendCulling = 0;      // caster/tile pairs removed by the culling factor
    uint32_t skippedByReceiverCulling = 0;   // ... whose shadow cannot reach the cascade's receivers
    double cullingMilliseconds = 0.0;        // CPU time spent culling casters per tile (both atlases)
};

struct DirectionalShadowPlan {
    AtlasLayout atlas;  // tileCount 0 when no light is reserved (the renderer may bind a 1x1 dummy)
    std::vector<ReservedDirectionalLight> lights;  // slots, in scene light order
    std::vector<CascadeSphere> cascades;           // shared by every light
    std::vector<ShadowTile> tiles;                 // tile i = light slot * cascadeCount + cascade
    std::vector<int32_t> slotOfSceneLight;         // per Scene::lights entry: slot, or -1
    bool tight = false;  // tight cascade fit (cascades selected by view depth), else culling spheres
    gpu_data::DirectionalShadowData gpu{};         // packed for the lit pass
    Aabb wsReceiverBounds;                         // every shadow receiver: how far shadows can reach
    float blendCullingFactor = 0.0f;               // Unity's shadowCascadeBlendCullingFactor
    uint32_t specializationMode = 0;               // gpu_data::kDirectionalShadows* bits the reserved lights need
    uint32_t specializationFilter = 0;             // their common filter (kShadowFilter*), or kShadowFilterFromData
};

// Spot and point light shadows in their own atlas, planned by shadows/spot_shadow_planner.
struct OtherShadowPlan {
    SpotAtlasLayout atlas;                   // tileCount 0 when no light is reserved
    std::vector<ReservedOtherLight> lights;  // slots, in scene light order
    std::vector<ShadowTile> tiles;           // tile i: lights[slot].firstTile + face (faces only for points)
    std::vector<int32_t> slotOfSceneLight;   // per Scene::lights entry: slot, or -1
    std::vector<uint32_t> droppedLights;     // scene indices that wanted shadows but did not fit
    std::vector<std::string> warnings;       // one line per dropped light
    uint32_t lightsConsidered = 0;           // spot and point lights in the scene
    uint32_t specializationMode = 0;         // gpu_data::kOtherShadowsHard | kOtherShadowsSoft bits, or kOtherShadowsVirtual
    double cullingMilliseconds = 0.0;        // CPU time of the per-tile caster culling
    gpu_data::OtherShadowData gpu{};         // packed for the lit pass
    // shadows.spot.mode = virtual: no atlas tiles (atlas.tileCount 0, `tiles` empty); instead face i of
    // the virtual shadow maps is where tile i would be (a light's firstTile is its first face), and
    // gpu.lights[slot].firstTile names it.
    bool virtualFaces = false;
    VirtualFaceConfig faceConfig;                 // shadows.virtual.faceResolution, pageSize
    std::vector<VirtualFace> faces;
    std::vector<VirtualFaceLight> faceLights;     // per slot
    float faceMarginTexels = 0.0f;                // the widest lookup reach of the reserved lights
};

struct ShadowFrame {
    DirectionalShadowPlan directional;
    OtherShadowPlan other;
    ShadowStats stats;
};

struct PlanOptions {
    // Fill ShadowTile::casterInstances by culling every caster against every tile on the CPU. The
    // renderer culls on the GPU (render/shadow_culling_pass) and turns this off; tests keep it as the
    // reference the GPU lists are compared with.
    bool cullCasters = true;
    // The version of the scene's casters and receivers when the caller keeps one, bumped by every change
    // to its instances or materials except the moves it reports with ShadowPlanWorkspace::instanceMoved
    // (the renderer's edits do): the workspace then keeps the caster list and the receivers' bounds of
    // the last plan of the same version instead of walking every instance again. 0: unknown, walk them
    // every time.
    uint64_t sceneVersion = 0;
};

// Working storage of ShadowPlanner::plan, kept by a caller that plans every frame.
struct ShadowPlanWorkspace {
    uint64_t sceneVersion = 0;          // PlanOptions::sceneVersion of casters and wsReceiverBounds (0: none)
    std::vector<uint32_t> casters;      // shadowCasterInstances
    Aabb wsReceiverBounds;              // shadowReceiverUnion
    std::vector<Aabb> receivers;        // the receivers' union, as blend culling reads it
    ReceiverVolume cameraReceivers;     // the frame's cameraReceiverVolume (invalid: receiver culling off)
    std::vector<Aabb> rsCasterBounds;   // one light's rotated caster bounds (PlanOptions::cullCasters)
    OtherLightReservation reservation;  // the spot and point lights' reservation
    uint64_t casterEpoch = 1;           // changes with the caster set and with every move (reserveOtherShadows)

    // Instance `instance` of `scene` moved from `wsOldBounds` (scene holds its new bounds): keeps the
    // caster list and the receivers' union exact in O(1) where it can - the union grows by the new
    // bounds, and the caster set changes only when the bounds become valid or invalid. Where it cannot
    // (the old bounds reached a face of the union that the new ones leave, or the set changes), the
    // next plan walks the instances again.
    void instanceMoved(const Scene& scene, uint32_t instance, const Aabb& wsOldBounds);
};

class ShadowPlanner {
public:
    // Settings must be valid (validateShadowSettings); scene and camera are read only. `visible` (the
    // frame's depth reduction) serves shadows.directional.fit = tight; without it the fit is the sphere.
    static ShadowFrame plan(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                            const VisibleSurfaces* visible = nullptr, const PlanOptions& options = {});
    // The same into `frame` (replaced): a frame planned into the ShadowFrame and workspace of the
    // frame before allocates nothing once the two have grown to the scene's size (with
    // PlanOptions::cullCasters off, as the renderer plans: the per-tile caster lists are the GPU's).
    static void plan(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                     const VisibleSurfaces* visible, const PlanOptions& options, ShadowFrame& frame,
                     ShadowPlanWorkspace& workspace);
};

}  // namespace penumbra
