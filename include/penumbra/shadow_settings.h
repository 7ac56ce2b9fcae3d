#pragma once
// The shadow part of the settings (the "shadows" block of the settings JSON, docs/settings.md).
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace penumbra {

enum class ShadowFilter { PCF2x2, PCF3x3, PCF5x5, PCF7x7 };
enum class CascadeBlend { Hard, Soft, Dither };
// How shadow depth is rasterized: the hardware pipeline, compute shaders (fast where few
// SMs run graphics, e.g. NVIDIA H100/H200), or auto: compute on datacenter NVIDIA GPUs (a table),
// elsewhere whichever the first frames measure faster.
enum class ShadowRaster { Hw, Compute, Auto };
// How the lit pass keeps surfaces from shadowing themselves (penumbra/shadows/bias.glsl):
// a constant normal offset, a normal offset scaled by sin(N, L), or receiver-plane depth bias.
// Every light's shadowNormalBias multiplies the automatic amount, its shadowBias adds a slope-scale bias.
enum class ShadowBiasMode { Normal, ScaledNormal, ReceiverPlane };
// How cascades are fitted: a culling sphere around the frustum slice, or
// tight to what the frame shows (a depth reduction: the visible surfaces' light-space bounds per slice).
enum class CascadeFit { Sphere, Tight };
// Where cascades split: given ratios of the shadow distance, logarithmic, or the "practical" blend
// lambda * log + (1 - lambda) * uniform over the depth range (the visible one with the tight fit).
enum class CascadeSplitMode { Manual, Log, Practical };
// The distance fade: linear in view depth over the last distanceFade of the shadow distance, or
// Unity URP's, linear in the squared camera distance over the same band.
enum class ShadowFadeMode { Linear, Squared };

// How directional lights are shadowed: cascaded shadow maps in the atlas (Unity's system), a virtual
// shadow map per light (a clipmap of pages drawn on demand and cached across frames), or auto: virtual
// on a GPU, cascades on a CPU device (where drawing pages costs more than the atlas). The default is
// cascades: the virtual maps' per-page culling lists do not yet fit scenes of 100k+ instances.
enum class DirectionalShadowMode { Cascades, Virtual, Auto };

// How spot and point lights are shadowed: tiles of the spot atlas (Unity's system), or virtual shadow
// maps: a face per spot light and six per point light, each a mip chain of pages drawn on demand and
// cached across frames. Auto: virtual on a GPU, the atlas on a CPU device (resolveSpotShadowMode).
enum class SpotShadowMode { Atlas, Virtual, Auto };

struct DirectionalShadowSettings {
    DirectionalShadowMode mode = DirectionalShadowMode::Auto;  // virtual on a GPU, cascades on a CPU device
    uint32_t atlasSize = 1024;
    ShadowFilter filter = ShadowFilter::PCF2x2;
    uint32_t cascadeCount = 4;
    std::array<float, 3> cascadeRatios{0.1f, 0.25f, 0.5f};
    float cascadeFade = 0.1f;
    CascadeBlend cascadeBlend = CascadeBlend::Hard;
    CascadeFit fit = CascadeFit::Tight;                   // measured best (docs/fidelity.md)
    CascadeSplitMode cascadeSplits = CascadeSplitMode::Log;  // measured best (docs/fidelity.md)
    float splitLambda = 0.75f;  // practical splits: weight of the logarithmic split, 0..1
    // Cull casters whose shadow cannot reach a receiver that samples the cascade (inside the camera's
    // frustum, the cascade's depth range or culling sphere): the image is the same.
    bool receiverCulling = true;
    bool operator==(const DirectionalShadowSettings&) const = default;
};

struct SpotShadowSettings {
    SpotShadowMode mode = SpotShadowMode::Auto;  // virtual on a GPU, the atlas on a CPU device
    uint32_t atlasSize = 1024;
    ShadowFilter filter = ShadowFilter::PCF5x5;
    // Constant clip-space depth bias of spot/point receivers, 0..1, subtracted from the
    // receiver's clip z before the divide. 0 by default: the lights' shadowNormalBias (default 1 =
    // one filter-texel diagonal at the fragment's distance) is the default bias. Measured
    // (lavapipe; canonical scenes at 256x144 via `penumbra compare`, misclassified % / MAE):
    //   normal bias 1, depthBias 0:      spot soft 0.344 / 0.0064, spot hard 0.156 / 0.0025, point 0.425 / 0.0067
    //   normal bias 0, depthBias 0.002:  0.025 / 0.0051, 0.078 / 0.0015, point 0.177 / 0.0820 (faint acne)
    //   normal bias 0, depthBias 0.005:  0.025 / 0.0046, 0.078 / 0.0015, point 0.120 / 0.0073
    // The constant bias gives sharper contacts on the spot scene, but no one value suits every light: its
    // world size is depthBias * d * (1/near - 1/far), so it depends on shadowNearPlane and on the tile's
    // resolution (point faces get small tiles and need 0.005 where spots need 0.0005), and at 0.005 the
    // grazing spot of tests/render/spot_bias_test.cpp peter-pans more than the normal bias (0.27 % vs
    // 0.19 %). The normal bias is in texels, so it is right at every near plane and tile size.
    float depthBias = 0.0f;
    bool operator==(const SpotShadowSettings&) const = default;
};

// The virtual shadow maps (shadows.directional.mode = virtual): each directional light's clipmap of
// `levelCount` levels of `resolution` virtual texels a side, level i firstLevelSize * 2^i metres wide, cut
// into pages of pageSize texels; a pool of poolPages physical pages per light. With shadows.spot.mode =
// virtual, the spot and point lights' faces: faceResolution virtual texels a side with mips down to one
// page, and one more pool of facePoolPages pages for all of them.
struct VirtualShadowSettings {
    uint32_t pageSize = 128;
    uint32_t resolution = 16384;
    // Rounded down to a square: 84^2 = 7056 pages of 128^2 texels of 16-bit depth codes, one R16_UNORM
    // image of 220.5 MiB (with the drawing's depth target of 484 pages of 32-bit depths, 251 MiB in all;
    // twice the image on a device without R16_UNORM storage images: render/virtual_page_storage.h).
    uint32_t poolPages = 7056;
    // The faces' pool, rounded down as well: 45^2 = 2025 pages, 63 MiB. More lets 16 lights at 1920x1080
    // read a mip finer (pool pressure coarsens them here: docs/rendering.md), at the cost of their pages'
    // and lookups' time.
    uint32_t facePoolPages = 2048;
    uint32_t levelCount = 16;
    float firstLevelSize = 2.0f;  // scene units (metres) along level 0's side
    // Levels finer (< 0) than the one whose texel matches a pixel's footprint: -1.5, a third less shimmer
    // than -1 for twice the pages (docs/fidelity.md).
    float lodBias = -1.5f;
    // The lodBias of a directional light whose direction changed in one of its last kVirtualMovingFrames
    // records: its pages are drawn again every frame, so a finer lodBias than this would cost a turning
    // light that many more pages (Unreal Engine's r.Shadow.Virtual.ResolutionLodBiasDirectionalMoving).
    float movingLodBias = -1.0f;
    bool cache = true;            // pages stay drawn across frames until invalidated
    uint32_t keepFrames = 8;      // frames an unrequested page stays resident
    uint32_t pagesPerFrame = 0;   // most dirty pages drawn in a frame per map (0: as many as its lists hold)
    uint32_t faceResolution = 8192;  // spot and point light faces: virtual texels along mip 0's side
    // The faces' lodBias: a perspective face's filter reaches further in the world at a coarser mip, so
    // they read finer texels than the clipmaps (measured: docs/fidelity.md, "Spot and point lights'
    // virtual shadow maps").
    float faceLodBias = -2.0f;
    bool operator==(const VirtualShadowSettings&) const = default;
};

struct ShadowSettings {
    ShadowBiasMode bias = ShadowBiasMode::ReceiverPlane;  // measured best (docs/fidelity.md)
    ShadowFadeMode fadeMode = ShadowFadeMode::Linear;
    float maxDistance = 100.0f;
    float distanceFade = 0.1f;
    bool screenSpace = false;
    ShadowRaster raster = ShadowRaster::Auto;
    // The compute rasterizer draws each caster with the coarsest simplified level of its mesh whose error
    // stays within this many texels of the tile or page it is drawn into (0: full meshes).
    float lodErrorTexels = 0.5f;
    // Cached shadow tiles: a tile whose light, projection and casters did not change since the last
    // frame keeps its depth and is not drawn again.
    bool cacheTiles = true;
    DirectionalShadowSettings directional;
    SpotShadowSettings spot;
    VirtualShadowSettings virtualMaps;  // the "shadows.virtual" keys
    bool operator==(const ShadowSettings&) const = default;
};

// Filter footprint in texels beyond the centre tap: PCF2x2 -> 0 ... PCF7x7 -> 3.
inline float filterSize(ShadowFilter filter) { return float(int(filter)); }

// Names as written in the settings JSON ("PCF5x5", "soft") and back; nullopt for an unknown name.
const char* shadowFilterName(ShadowFilter filter);
const char* cascadeBlendName(CascadeBlend blend);
const char* shadowBiasModeName(ShadowBiasMode mode);
std::optional<ShadowBiasMode> parseShadowBiasMode(const std::string& name);
const char* shadowFadeModeName(ShadowFadeMode mode);
std::optional<ShadowFadeMode> parseShadowFadeMode(const std::string& name);
const char* cascadeFitName(CascadeFit fit);
std::optional<CascadeFit> parseCascadeFit(const std::string& name);
const char* cascadeSplitModeName(CascadeSplitMode mode);
std::optional<CascadeSplitMode> parseCascadeSplitMode(const std::string& name);
std::optional<ShadowFilter> parseShadowFilter(const std::string& name);
std::optional<CascadeBlend> parseCascadeBlend(const std::string& name);
const char* shadowRasterName(ShadowRaster raster);
const char* directionalShadowModeName(DirectionalShadowMode mode);
const char* spotShadowModeName(SpotShadowMode mode);
std::optional<ShadowRaster> parseShadowRaster(const std::string& name);

// Checks the ranges of settings_keys.h; throws Error naming the first bad key with its allowed range, e.g.
// "settings: shadows.directional.cascadeCount = 7 is out of range (allowed 1..4)".
void validateShadowSettings(const ShadowSettings& settings);

}  // namespace penumbra
