#pragma once
// Renderer::State: what a Renderer keeps across frames (its passes, targets, caches and the frames
// still on the GPU), shared by renderer.cpp (the public API, construction) and renderer_frame.cpp
// (recording, submitting and collecting a frame).
#include <memory>
#include <optional>
#include <vector>

#include "core/recycling_queue.h"
#include "penumbra/shadow_system.h"
#include "penumbra/shadows/bindings.h"
#include "gpu/device.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "render/atlas_copy_pass.h"
#include "render/compute_raster_pass.h"
#include "render/frame_readback.h"
#include "render/frame_targets.h"
#include "render/gpu_scene.h"
#include "render/light_cluster_pass.h"
#include "render/light_packing.h"
#include "render/main_pass.h"
#include "render/raster_choice.h"
#include "render/screen_space_shadow_pass.h"
#include "render/shadow_caster_pass.h"
#include "render/shadow_culling_pass.h"
#include "render/tile_cache.h"
#include "render/virtual_face_shadows.h"
#include "render/virtual_settling.h"
#include "render/virtual_shadows.h"
#include "render/visibility_pass.h"
#include "render/visible_surface_pass.h"
#include "shadows/cull_packing.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

// An imported caller image, remembered so a swapchain's images are imported once each.
struct ImportedImage {
    uint64_t vkImage = 0;
    uint32_t width = 0, height = 0, format = 0;
    gpu::TextureHandle texture;
    uint64_t vkImageView = 0;  // a caller's depth view (ShadowViewDepth)
};
constexpr size_t kMaxImportedImages = 8;

// What a submitted frame still owes its caller once the GPU is done.
struct PendingFrame {
    uint64_t frameIndex = 0;
    FrameStats stats;
    ShadowFrame plan;  // the stats JSON is written once the GPU's cull counts are back
    FrameReadbackLayout readback;
    bool computeRaster = false;
    // What the atlases' compute rasterizer skips and simplifies: full meshes unless every frame draws the
    // atlases with it (RasterChoice::computeForGood), so that both paths give one shadow whichever runs.
    ShadowRasterOptions atlasRaster;
    bool autoRaster = false;      // shadows.raster = auto and still measuring: its timings feed the choice
    bool visibilityView = false;  // the main view came from the visibility buffer
    bool autoMainView = false;    // render.mainView = auto and still measuring: its main pass time feeds the choice
    // The page update of the directional maps / the faces was skipped (render/virtual_settling.h).
    bool virtualSettled = false, facesSettled = false;
    // What the tight fit's reduction of this frame's depth is recorded with (readback.visibleSurfaces).
    gpu_data::VisibleBoundsData visibleBounds{};
    ShadowRaster rasterSetting = ShadowRaster::Auto;
    MainView mainViewSetting = MainView::Auto;
};

// One frame being recorded: what submit() decided and uploaded, passed along its recording steps.
struct FrameRecording {
    gpu::CommandList& commands;
    PendingFrame& frame;
    const Settings& settings;
    const CameraView& view;
    const FrameTargetSizes& sizes;
    std::vector<gpu::DescriptorWrite>& casterWrites;  // scene bindings 0-4 (the State's storage)
    const char* stage = "scene updates";  // the part being recorded, named by a failure
    // Upload ring slices, all made before the frame's first readback (Device::allocateFrameData).
    gpu::BufferSlice frameSlice, lightSlice, clusterSlice, shadowViewSlice, directionalSlice, otherSlice, cullSlice;
    gpu::BufferSlice cullTileSlice;        // the culling pass's tile list (CullTileUpload)
    gpu::BufferSlice visibleBoundsSlice;   // the tight fit's VisibleBoundsData (frame.visibleBounds)
    gpu::BufferSlice rasterListSlices[2];  // each atlas pass's raster list (RasterTileUpload)
    bool clustered = false;    // the spot/point lights go through the light clusters
    bool screenSpace = false;  // URP's screen-space resolve of the directional shadows
    bool viewGeometryDone = false;  // the visibility buffer's geometry is recorded: the main view only shades
    gpu::TextureHandle prepassDepth;  // the depth prepass's depth, when this frame recorded one
    gpu::TextureHandle callerDepth;   // a ShadowSystem caller's depth of the view, in place of the prepass
    float clearColor[4] = {0, 0, 0, 1};  // the main view's: 1 (lit) for the shadow AOV, else black
    bool backgroundGradient = false;      // the colour output's render.background gradient behind the surfaces
};

// A failure while frame `frameIndex` was at `stage`, as one line naming both.
Error frameFailure(uint64_t frameIndex, const std::string& stage, const Error& error);

// Whether directional lights use virtual shadow maps (shadows.directional.mode = virtual).
inline bool virtualDirectional(const Settings& settings) {
    return settings.shadows.directional.mode == DirectionalShadowMode::Virtual;
}

// Whether frames reduce the view's depth for the tight cascade fit (fit = tight; virtual maps fit no cascades).
inline bool tightCascadeFit(const Settings& settings) {
    return settings.shadows.directional.fit == CascadeFit::Tight && !virtualDirectional(settings);
}

// The shadow tiles a frame draws (indices into the plan's tiles of each atlas), the rest cached.
struct TilesToDraw {
    std::vector<uint32_t> directional, other;
    bool freshDirectional = false, freshOther = false;  // the atlas is new: nothing to keep, clear it
};

// The descriptors of <penumbra/shadows.glsl> after a shadow frame, binding kShadowBinding* each.
using ShadowFrameWrites = std::array<gpu::DescriptorWrite, kShadowBindingCount>;

struct Renderer::State {
    gpu::Device& device;
    Scene scene;
    RendererOptions options;
    GpuScene gpuScene;
    ShadowCullingPass culling;
    MainPass mainPass;
    ShadowCasterPass casterPass;
    AtlasCopyPass atlasCopy;  // either rasterizer's depth -> the sampled R32F atlases
    ScreenSpaceShadowPass screenSpacePass;
    VisibleSurfacePass visiblePass;
    ComputeRasterPass computeRaster;
    VirtualShadows virtualShadows;  // shadows.directional.mode = virtual (draws with computeRaster)
    VirtualFaceShadows virtualFaces;  // shadows.spot.mode = virtual (draws with computeRaster)
    ComputeRasterPass::AtlasTiles atlasTilesScratch;  // recordShadowAtlases: the tiles an atlas pass draws
    LightClusterPass lightClusters;
    RasterChoice rasterChoice;
    std::unique_ptr<VisibilityPass> visibility;  // made by the first visibility-buffer frame
    RasterChoice mainViewChoice;
    std::optional<VisibleSurfaces> latestVisible;  // the tight fit's reduction of the latest finished frame
    glm::uvec2 latestVisibleSize{0};
    uint64_t editBytesUploaded = 0;  // this frame's scene edits that uploadSceneEditsNow sent ahead of it
    bool facesWentCoarser = false;  // a finished frame overflowed the faces' pool: their lodBias went a step coarser
    glm::uvec3 rasterNeeded{0};  // the most large pieces / chunks / work items a finished frame asked the compute rasterizer for
    TileCache directionalCache, otherCache;
    uint64_t directionalGenerationDrawn = ~0ull, otherGenerationDrawn = ~0ull;  // atlases the caches hold tiles of
    float tilesLodErrorTexels = 0.0f;  // PendingFrame::atlasRaster.lodErrorTexels the cached tiles were drawn with
    uint64_t sceneVersion = 0;  // bumped by every change to the casters (transforms, cast flags, materials)
    // Bumped by the changes that can add or remove casters or receivers (cast flags, materials): the
    // planner's workspace follows moves itself (ShadowPlanWorkspace::instanceMoved).
    uint64_t casterSetVersion = 0;
    uint64_t lightVersion = 0;  // bumped by every change to a light
    // Shadow frames on a caller's depth so far: the virtual pages' settling counts each as new inputs
    // (the caller's geometry may move with nothing else changing), so none settles.
    uint64_t callerDepthFrames = 0;
    VirtualSettling virtualSettling;
    FrameTargets targets;
    gpu::SamplerHandle pointSampler;
    gpu::TextureHandle noScreenShadows;  // bound at binding 9 when the screen-space resolve is off
    std::vector<ImportedImage> imported;
    ImportedImage callerDepth;  // a ShadowSystem caller's depth image, imported once
    // Submitted frames, oldest first, and the finished frames' stats not yet taken: both recycle their
    // elements (a steady-state frame reuses the storage of the frames before it).
    RecyclingQueue<PendingFrame> pending;
    RecyclingQueue<FrameStats> completed;
    ShadowPlanWorkspace planWorkspace;
    PackedLights packedLights;
    MainPassInputs mainInputs;
    std::vector<gpu::DescriptorWrite> casterWrites;
    MainPassVariant litPassScratch;  // prepareMainView's
    MainPass::Target mainTarget;     // recordMainView's
    VisibilityPass::Target opaqueTarget;
    double lastGpuFrameEnd = 0.0;  // the latest finished frame's CompletedFrame::gpuEndMilliseconds
    // Lists every frame refills, kept so a steady-state frame reuses their storage.
    std::vector<TileSignature> directionalSignatures, otherSignatures;
    TilesToDraw drawnTiles;
    // The tile lists uploaded each frame (fixed arrays: nothing allocated per frame).
    CullTileUpload cullTileUpload;
    RasterTileUpload rasterTileUploads[2];
    std::vector<gpu_data::ShadowLightSlot> shadowLightTable;  // a shadow frame's light table
    gpu::BufferSlice shadowLightTableSlice, shadowViewSlice;   // its light table and camera, uploaded
    std::vector<gpu::ResourceUse> shadowHandOverUses;         // and what its hand-over declares

    State(gpu::Device& d, Scene s, const RendererOptions& o);
    ~State();
    void destroyOwnObjects();
    // Every variant a setting can reach: the generic sets first (what frames fall back on), then the
    // specialized ones.
    void requestAllVariants();
    gpu::TextureHandle importedTexture(const ExternalImage& target);

    // renderer_frame.cpp. oneShot: the caller waits for this frame (render()): the tight fit reduces
    // this very view's depth.
    void checkRequest(const RenderRequest& request, const CameraView& view) const;
    uint64_t submit(const RenderRequest& request, const Settings& settings, const CameraView& view,
                    const ExternalImage* target, bool readback, bool captureAtlas, bool oneShot);
    void collectCompleted();
    // ShadowSystem's frame (renderer_shadow_frame.cpp): the shadows alone, recorded into the caller's
    // command buffer; `writes` gets what <penumbra/shadows.glsl> binds. The caller submits the command
    // buffer, signalling the returned timeline value, before the next frame.
    // depth: the caller's depth of the view, or null.
    gpu::Device::ExternalFrameEnd recordShadowFrame(uint64_t vkCommandBuffer, const Settings& settings,
                                                    const CameraView& view, const ShadowViewDepth* depth,
                                                    ShadowFrameWrites& writes);

    // Scene changes between frames (Renderer's and ShadowSystem's; renderer.cpp).
    void setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject);
    void setInstanceCastShadows(uint32_t instance, bool castShadows);
    void setLight(uint32_t light, const Light& value);
    void setMaterial(uint32_t material, const Material& value);

    // Every virtual shadow map: a caster whose bounds changed (before and after), or everything redrawn.
    void casterChanged(const Aabb& wsBounds) {
        virtualShadows.casterChanged(wsBounds);
        virtualFaces.casterChanged(wsBounds);
        virtualSettling.unsettle();
    }
    void invalidateVirtualMaps() {
        virtualShadows.invalidateAll();
        virtualFaces.invalidateAll();
        virtualSettling.unsettle();
    }

private:
    uint64_t submitInto(PendingFrame& frame, const RenderRequest& request, const Settings& settings,
                        const CameraView& view, const ExternalImage* target, bool readback, bool captureAtlas,
                        bool oneShot);
    static void resetPendingFrame(PendingFrame& frame);
    // The CPU half of a frame (renderer_frame.cpp): the settings fitted to the device (in place), the
    // main view chosen (none when shadowsOnly), the shadows planned, the lights packed, the virtual maps
    // begun and the targets made; returns the targets' sizes.
    FrameTargetSizes planFrame(PendingFrame& frame, Settings& settings, const CameraView& view, OutputMode output,
                               bool oneShot, bool shadowsOnly, bool& visibilityWanted);
    void dropRecordedTiles();  // after a frame that failed while recording
    // The steps of submit(), in order.
    bool chooseMainView(const Settings& settings, PendingFrame& frame) const;  // true: the visibility pass is wanted
    // The tight fit's visible surfaces of this very view, when the frame cannot plan with a finished one's.
    std::optional<VisibleSurfaces> tightFitSurfacesNow(const Settings& settings, const CameraView& view, bool oneShot);
    // Submits the scene edits not yet on the GPU in a frame of their own (before a pass that reads the
    // scene ahead of the next frame); returns the bytes copied.
    uint64_t uploadSceneEditsNow();
    void planShadows(PendingFrame& frame, const Settings& settings, const CameraView& view,
                     const std::optional<VisibleSurfaces>& visibleNow);
    // The frame's lit pass variant; makes what the visibility-buffer main view needs when it may draw.
    const MainPassVariant& prepareMainView(const Settings& settings, const ShadowFrame& plan, const FrameTargetSizes& sizes,
                                    bool visibilityWanted);
    void uploadFrameInputs(FrameRecording& recording, const RenderRequest& request, const PackedLights& lights);
    const TilesToDraw& chooseTilesToDraw(FrameRecording& recording);
    void recordShadowAtlases(FrameRecording& recording, const TilesToDraw& draw);
    MainPassInputs& recordLightingInputs(FrameRecording& recording);
    // The view's depth before anything shades, the virtual shadow maps' pages from it (virtual mode),
    // then the screen-space resolve (shadows.screenSpace). renderer_virtual.cpp.
    void recordViewShadowInputs(FrameRecording& recording, MainPassInputs& inputs, const MainPassVariant& litPass);
    void recordScreenSpaceShadows(FrameRecording& recording, MainPassInputs& inputs);
    // The forward depth prepass of the view, recorded by the first step of the frame that needs it.
    gpu::TextureHandle prepassDepthOf(FrameRecording& recording, MainPassInputs& inputs);
    // The visibility buffer's targets and constants for this frame (opaqueTarget, refilled).
    const VisibilityPass::Target& opaqueTargetFor(const FrameRecording& recording, const MainPassVariant& litPass);
    void recordMainView(FrameRecording& recording, MainPassInputs& inputs,
                        const MainPassVariant& litPass, bool oneShot);
    gpu::ExternalTarget recordOutputs(FrameRecording& recording, const ExternalImage* target, bool readback,
                                      bool captureAtlas);
    void finishFrame(gpu::CompletedFrame& done, PendingFrame& finished);
    void settleVirtualPages(PendingFrame& finished);
    gpu::Device::ExternalFrameEnd recordShadowFrameInto(PendingFrame& frame, uint64_t vkCommandBuffer,
                                                        const Settings& settings, const CameraView& view,
                                                        const ShadowViewDepth* depth, ShadowFrameWrites& writes);
    gpu::TextureHandle importedDepth(const ShadowViewDepth& depth, const CameraView& view);
    void uploadShadowHandOver(FrameRecording& recording);
    void recordShadowFitDepth(FrameRecording& recording, MainPassInputs& inputs);
    // The tight fit's reduction of the view's depth, read back for the next frames' plans: its data is
    // uploaded with the frame's inputs (before any readback), the pass recorded after the depth.
    void uploadVisibleBoundsData(FrameRecording& recording);
    void recordVisibleBounds(FrameRecording& recording, gpu::TextureHandle depth);
    void handOverShadowBindings(FrameRecording& recording, const MainPassInputs& inputs, ShadowFrameWrites& writes);
};

}  // namespace penumbra
