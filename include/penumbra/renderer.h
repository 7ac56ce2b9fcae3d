#pragma once
// The real-time renderer: it owns a scene's GPU data, its render targets and shadow atlases, and
// renders frame after frame. Each frame plans the shadows on the CPU (lights, cascades, atlas tiles,
// caster lists), then records the shadow atlas passes, the optional depth prepass and screen-space
// shadow resolve, the opaque + unlit pass, the transparent pass, and reads back the colour image or
// a debug AOV only when asked. Frames in flight run in a ring (DeviceOptions::framesInFlight): a
// steady-state frame makes no GPU object, builds no pipeline, waits for no more than the frame that
// used its ring slot before, and makes one queue submission.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <penumbra/camera.h>
#include <penumbra/device.h>
#include <penumbra/image.h>
#include <penumbra/scene.h>
#include <penumbra/settings.h>
#include <penumbra/shadow_stats.h>

namespace penumbra {

enum class OutputMode { Color, ShadowAov, CascadesAov };

struct RenderRequest {
    uint32_t width = 1280;
    uint32_t height = 720;
    OutputMode output = OutputMode::Color;
    uint32_t aovLight = 0;      // index into Scene::lights for --aov shadow / cascades
    bool captureAtlas = false;  // render(): also the shadow atlases' depth (RenderResult::atlas)
    bool readback = true;       // render(): copy the image to host memory (RenderResult::image)
};

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

// CPU time of one frame, per phase, in milliseconds.
struct CpuPhaseTimes {
    double plan = 0.0;     // shadow planning without caster culling (lights, cascades, tiles, packing)
    double culling = 0.0;  // caster culling per tile
    double upload = 0.0;   // frame data and scene changes into the upload ring
    double record = 0.0;   // command recording
    double submit = 0.0;   // vkQueueSubmit
    double readback = 0.0; // the finished frame's results on the host (tight-fit depth bounds, virtual page
                           // requests, timings), done when a later call collects the frame
    // plan + culling + upload + record + submit in the calling thread's CPU time: without the time the
    // thread was not running (the host's), with what the thread itself spent (the engine's).
    double thread = 0.0;
};

// What one shadow atlas pass drew.
struct AtlasDrawStats {
    std::string pass;  // "shadows.directional", "shadows.other"
    uint32_t tiles = 0;
    uint32_t draws = 0;
    uint64_t triangles = 0;
};

// Virtual shadow map pages of one frame (shadows.directional.mode = virtual), summed over the
// directional lights' maps; all 0 with cascades.
struct VirtualPageCounts {
    uint32_t maps = 0;        // directional lights with a virtual map (spot and point faces: the faces)
    uint32_t requested = 0;   // pages the view's lookups read (the marking pass)
    uint32_t cached = 0;      // requested pages already resident
    uint32_t allocated = 0;   // requested pages given a physical page this frame
    uint32_t drawn = 0;       // pages drawn this frame (new, or invalidated by a light or a caster)
    uint32_t evicted = 0;     // resident pages freed (left the window, idle too long, or taken for another)
    uint32_t overflowed = 0;  // requested pages that found no physical page: a coarser level served them
    // Requested pages to draw past what one frame draws (its culling lists' budget, docs/rendering.md
    // "Pages per frame"): the finest wait for the next frames, a coarser level serving them meanwhile.
    uint32_t deferred = 0;
    uint32_t resident = 0;    // resident pages after the frame
    uint32_t poolPages = 0;   // physical pages of all the maps' pools
    uint32_t pagesPerFrame = 0;  // the most pages all the maps draw in one frame (shadows.virtual.pagesPerFrame, lists)
    // Pool pressure (spot and point faces): steps coarser than shadows.virtual.faceLodBias the pages were
    // marked and read at, after earlier frames overflowed the pool (0..2).
    uint32_t lodBiasSteps = 0;
    // The page update was skipped: the frame's inputs (camera, settings, casters, lights) equal those of a
    // finished frame that found every requested page resident and drew nothing; that frame's requested,
    // cached and resident counts are repeated (docs/rendering.md, "Settled frames").
    bool settled = false;
};

struct FrameStats {
    uint64_t frameIndex = 0;
    std::vector<PassTiming> gpuTimings;  // per pass, from timestamps (empty where the device has none)
    CpuPhaseTimes cpu;
    double submitToFenceMilliseconds = 0.0;  // from the submission to the fence seen signalled
    // GPU timestamps (0 without them): the frame's commands first to last, and the frame period, from
    // the end of the previous finished frame's commands to the end of this one's (what the GPU
    // sustains when frames are submitted back to back; idle time between frames counts).
    double gpuFrameMilliseconds = 0.0, gpuFramePeriodMilliseconds = 0.0;
    uint64_t sceneBytesUploaded = 0;         // changed instances and materials copied this frame
    std::string shadowRaster = "hw";         // the rasterizer that drew this frame's shadow maps: hw | compute
    std::string shadowRasterChoice;          // shadows.raster = auto: how it was chosen
    std::string mainView = "forward";        // how the main view was drawn: forward | visibility
    std::string mainViewChoice;              // how it was chosen: "render.mainView = forward|visibility", or auto's choice (or "measuring")
    // How this frame's directional lights were shadowed: "cascades" or "virtual" (shadows.directional.mode,
    // with auto resolved for the device: virtual on a GPU, cascades on a CPU device).
    const char* directionalShadows = "cascades";
    // How this frame's spot and point lights were shadowed: "atlas" or "virtual" (shadows.spot.mode, auto
    // resolved as above: virtual on a GPU, the atlas on a CPU device).
    const char* spotShadows = "atlas";
    // The tight cascade fit reduced this frame's own view depth and waited for it (one-shot frames, and
    // the first real-time frame; later ones plan from the latest finished reduction).
    bool tightFitWaited = false;
    // The visibility buffer's GPU culling (render.viewCulling): the opaque and alpha-tested instances
    // with geometry, those drawn in the early phase (the frustum's instances visible last frame) and the
    // late one (found visible by the depth pyramid), and their triangles; all 0 for forward frames.
    uint32_t viewInstances = 0, viewInstancesEarly = 0, viewInstancesLate = 0;
    uint64_t viewTriangles = 0;
    // Meshlets the compute rasterizers skipped (render.meshletCulling): in the shadow atlases, those
    // outside their tile; in the visibility buffer, those outside the view and those facing away.
    uint64_t shadowMeshletsOutside = 0, viewMeshletsOutside = 0, viewMeshletsFacingAway = 0;
    // The compute rasterizer (both atlases and the virtual pages): its work items (a few meshlets of one
    // instance, or several small instances, in one tile or page), the medium triangle pieces a workgroup
    // rasterized together, large pieces split into chunks, the chunks, and what its queues could not hold
    // (drawn incompletely, then drawn again: a warning names it).
    // Of the work items, those drawing a simplified level of their mesh (shadows.lodErrorTexels).
    uint64_t rasterSimplifiedItems = 0;
    uint64_t rasterWorkItems = 0, rasterMediumTriangles = 0, rasterLargeTriangles = 0, rasterChunks = 0, rasterDropped = 0;
    // Shadow tiles drawn this frame and kept from earlier frames (shadows.cacheTiles).
    uint32_t tilesRendered = 0, tilesReused = 0;
    // Clustered light culling (render.lightCulling): the spot and point lights per cluster, mean over
    // all clusters and most in one; 0 when the frame had no spot or point light or culling was off.
    double lightsPerClusterMean = 0.0;
    uint32_t lightsPerClusterMax = 0;
    std::vector<AtlasDrawStats> atlases;
    VirtualPageCounts virtualPages;
    // Per directional light with a virtual map (the first virtualPages.maps), per level (finest first):
    // the page view of the viewer and of --stats.
    struct VirtualMapLevels {
        uint32_t levelCount = 0;
        std::array<uint32_t, 16> requested{}, cached{}, drawn{};  // cached: requested and already resident
    };
    std::array<VirtualMapLevels, 4> virtualMaps{};
    // The same for the spot and point lights' faces (shadows.spot.mode = virtual; maps = faces), their
    // levels the mips (finest first, every face together).
    VirtualPageCounts virtualFacePages;
    VirtualMapLevels virtualFaceMips;
    std::vector<std::string> warnings;
    // The shadow plan (lights reserved, tiles, casters and triangles per tile) as plain data; toJson()
    // writes it as --stats prints it.
    ShadowPlanStats shadows;
};

// The frame's stats as one JSON object, as `penumbra render --stats` prints them after the device and
// the size (docs/cli.md lists the keys): gpuMs, cpuPlanMs, cpuMs, shadows, warnings, shadowRaster,
// mainView, meshletsSkipped, tiles, lightsPerCluster, virtualPages, virtualFacePages.
std::string toJson(const FrameStats& stats);

struct RenderResult {
    Image image;  // RGB colour (sRGB) or 1-channel AOV; empty when request.readback is false
    Image atlas;  // 1-channel depth of the shadow atlases when requested
    FrameStats stats;
};

// How the renderer gets the pipeline variants a setting can reach (the spot/point shadow kinds and
// filter of the lit pass, the colour formats of the outputs).
enum class PipelineWarmup {
    OnDemand,    // build a variant when a frame first needs it (one-shot renders: builds only what is used,
                 // and a variant compiles only the sampling of the frame's directional and spot/point kinds)
    Background,  // build every variant that settings can reach for the scene's lights as they are (a
                 // light edited into another kind builds its variant on demand) on the device's worker
                 // thread from the start; until a variant is ready, frames use the generic variant (same
                 // image), so no frame stalls. On a CPU device (lavapipe), whose shaders compile when first
                 // drawn, a frame waits for its own variant instead of drawing the generic one
};

struct RendererOptions {
    PipelineWarmup warmup = PipelineWarmup::OnDemand;
    // Testing and debugging: always draw with the generic lit-pass variant (it must give the same image).
    bool forceGenericVariants = false;
    // The compute rasterizer's queues of large triangle pieces, of their chunks and of its work items
    // (a few meshlets of one instance in one tile or page) start this large (0 = the defaults, 256k,
    // 1M and 64k) and grow when a frame overflows them.
    uint32_t rasterLargeQueue = 0, rasterChunkQueue = 0, rasterWorkQueue = 0;
};

// A caller-owned image to render into (see <penumbra/vulkan.h>, which fills it from Vulkan types).
struct ExternalImage {
    uint64_t vkImage = 0;          // VkImage on the Device's VkDevice, with TRANSFER_DST usage
    uint32_t vkFormat = 0;         // VkFormat (a blit destination format)
    uint32_t width = 0, height = 0;
    uint32_t vkInitialLayout = 0;  // VkImageLayout at the start of the frame (UNDEFINED discards it)
    uint32_t vkFinalLayout = 0;    // VkImageLayout the frame leaves it in
    uint64_t vkWaitSemaphore = 0;  // binary VkSemaphore to wait on before writing it, or 0
    uint64_t vkWaitStageMask = 0;  // VkPipelineStageFlags2 of that wait (0 = all commands)
    uint64_t vkSignalSemaphore = 0;  // binary VkSemaphore signalled once it is written, or 0
};

class Renderer {
public:
    Renderer(Device& device, Scene scene, const RendererOptions& options = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const Scene& scene() const;

    // ---- scene changes between frames: the next frame uploads only what changed.
    void setInstanceTransform(uint32_t instance, const glm::mat4& worldFromObject);
    void setInstanceCastShadows(uint32_t instance, bool castShadows);
    void setLight(uint32_t light, const Light& value);
    // Everything but the base-colour texture index may change (colour, alpha mode and cutoff, shadow
    // mode, receive shadows, unlit, double-sided).
    void setMaterial(uint32_t material, const Material& value);

    // ---- one frame, waited for: the CLI's render, the tests.
    RenderResult render(const RenderRequest& request, const Settings& settings);
    RenderResult render(const RenderRequest& request, const Settings& settings, const CameraView& view);

    // ---- real time: records and submits a frame and returns its index without waiting for it
    // (only for the frame that last used the same ring slot). With `target`, the frame's colour or AOV
    // is blitted into that caller-owned image. request.readback and captureAtlas are ignored here.
    uint64_t submitFrame(const RenderRequest& request, const Settings& settings, const CameraView& view,
                         const ExternalImage* target = nullptr);
    // Stats of the frames the GPU has finished since the last call, oldest first.
    std::vector<FrameStats> takeCompletedFrames();
    // The same into `frames` (replaced), for a loop that calls it every frame with the same vector:
    // its elements are exchanged with the renderer's, so once warm neither side allocates.
    void takeCompletedFrames(std::vector<FrameStats>& frames);
    void waitIdle();

    // Pipeline variants still building on the worker thread (PipelineWarmup::Background).
    uint32_t pipelineBuildsPending() const;
    // Blocks until every variant a setting can reach is built.
    void buildAllPipelines();

private:
    friend class ShadowSystem;  // runs the same State, frames of shadows only (shadow_system.h)
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace penumbra
