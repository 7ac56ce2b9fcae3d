// The table of every settings key (penumbra/settings_keys.h) and the validation it drives.
#include "penumbra/settings_keys.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace penumbra {

namespace {

template <typename T>
double toNumber(T value) {
    if constexpr (std::is_enum_v<T>) return double(int(value));
    else return double(value);
}

template <typename T>
T fromNumber(double value) {
    if constexpr (std::is_enum_v<T>) return T(int(value));
    else if constexpr (std::is_same_v<T, bool>) return value != 0.0;
    else return T(value);
}

// get / set of one field of Settings.
#define PENUMBRA_FIELD(field)                                                             \
    [](const Settings& s, size_t) { return toNumber(s.field); },                          \
        [](Settings& s, size_t, double v) { s.field = fromNumber<decltype(s.field)>(v); }

constexpr double kHuge = 3.0e38;

const std::vector<std::string> kFilters = {"PCF2x2", "PCF3x3", "PCF5x5", "PCF7x7"};

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

SettingKey choice(const char* key, std::vector<std::string> names, double (*get)(const Settings&, size_t),
                  void (*set)(Settings&, size_t, double), std::string description) {
    SettingKey setting{key, SettingType::Choice, 0.0, double(names.size() - 1)};
    setting.allowed = joined(names);
    setting.choices = std::move(names);
    setting.description = std::move(description);
    setting.get = get;
    setting.set = set;
    return setting;
}

SettingKey ranged(const char* key, SettingType type, double min, double max, const char* allowed,
                  double (*get)(const Settings&, size_t), void (*set)(Settings&, size_t, double), std::string description) {
    SettingKey setting{key, type, min, max};
    setting.allowed = allowed;
    setting.description = std::move(description);
    setting.get = get;
    setting.set = set;
    return setting;
}

SettingKey flag(const char* key, double (*get)(const Settings&, size_t), void (*set)(Settings&, size_t, double),
                std::string description) {
    return ranged(key, SettingType::Bool, 0, 1, "true, false", get, set, std::move(description));
}

// The two atlases' keys: their size and the filter of their lights' soft shadows.
SettingKey atlasSizeKey(const char* key, double (*get)(const Settings&, size_t), void (*set)(Settings&, size_t, double),
                        const char* holds) {
    return ranged(key, SettingType::PowerOfTwo, 256, 8192, "a power of two in 256..8192", get, set,
                  std::string("Side in texels of the ") + holds);
}

SettingKey filterKey(const char* key, double (*get)(const Settings&, size_t), void (*set)(Settings&, size_t, double),
                     const char* lights) {
    return choice(key, kFilters, get, set,
                  std::string("The filter of ") + lights +
                      " with `shadows: \"soft\"`: one bilinear 2x2 PCF tap, or a 3x3, 5x5 or 7x7 tent filter.");
}

// The shadow keys first, then "render"; validation reports the first bad one in this order, and
// docs/settings.md lists them in it.
std::vector<SettingKey> makeTable() {
    std::vector<SettingKey> t;
    t.push_back(choice("shadows.bias", {"normal", "scaledNormal", "receiverPlane"}, PENUMBRA_FIELD(shadows.bias),
                       "How the lit pass keeps a surface from shadowing itself: `normal` offsets the receiver along its "
                       "normal by a constant number of texels, `scaledNormal` scales that offset by the sine of the "
                       "angle between normal and light, `receiverPlane` compares every texel a filter reads with the "
                       "depth of the receiver's plane at that texel's centre. A light's `shadowNormalBias` multiplies the "
                       "automatic amount and its `shadowBias` adds a slope-scale term."));
    t.push_back(choice("shadows.fadeMode", {"linear", "squared"}, PENUMBRA_FIELD(shadows.fadeMode),
                       "How shadows fade out over the last `distanceFade` of the shadow distance: `linear` in view "
                       "depth, or `squared` (Unity URP's) linear in the squared distance to the camera."));
    t.push_back(ranged("shadows.maxDistance", SettingType::Number, 0.001, kHuge, ">= 0.001", PENUMBRA_FIELD(shadows.maxDistance),
                       "The shadow distance in scene units: nothing farther from the camera (or beyond its far plane, "
                       "when nearer) receives a directional shadow, and the cascades split this range. When it is not "
                       "set and the scene lies wholly beyond 100 units of the camera or within 1 unit, the programs "
                       "use the distance to the scene's farthest corner instead, with a warning."));
    t.push_back(ranged("shadows.distanceFade", SettingType::Number, 0.001, 1.0, "0.001..1", PENUMBRA_FIELD(shadows.distanceFade),
                       "The share of the shadow distance, at its far end, over which shadows fade out."));
    t.push_back(flag("shadows.screenSpace", PENUMBRA_FIELD(shadows.screenSpace),
                       "Screen-space shadows for the main directional light, as in Unity URP: a depth and normal "
                       "prepass, then a full-screen pass writes the light's shadow term, which the lit pass reads."));
    t.push_back(choice("shadows.raster", {"hw", "compute", "auto"}, PENUMBRA_FIELD(shadows.raster),
                       "How shadow depth is rasterized: `hw` by the graphics pipeline, `compute` by compute shaders "
                       "(fast where few SMs run graphics, e.g. NVIDIA H100 / H200), `auto` by a table on datacenter "
                       "NVIDIA GPUs (compute, no measuring frames) and elsewhere by whichever the first frames measure "
                       "faster. Both give the same shadow term."));
    t.push_back(ranged("shadows.lodErrorTexels", SettingType::Number, 0.0, 4.0, "0..4", PENUMBRA_FIELD(shadows.lodErrorTexels),
                       "The compute rasterizer draws each shadow caster with the coarsest simplified level of its mesh "
                       "(up to 4, made by meshoptimizer at load) whose error, scaled to the instance, stays within "
                       "this many texels of the tile or page it is drawn into at the caster's nearest point: a far "
                       "cascade or coarse page draws a few triangles of a detailed mesh. 0 draws every caster in "
                       "full; alpha-tested casters and the `hw` rasterizer always are, and so are the atlases' "
                       "casters unless every frame draws them by compute (`shadows.raster = compute`, or `auto` "
                       "where the device table decides), so that both rasterizers give one shadow."));
    t.push_back(flag("shadows.cacheTiles", PENUMBRA_FIELD(shadows.cacheTiles),
                       "A shadow tile whose projection, cascade spheres, casters and rasterizer did not change since the "
                       "last frame keeps its depth and is not drawn again."));
    t.push_back(choice("shadows.directional.mode", {"cascades", "virtual", "auto"}, PENUMBRA_FIELD(shadows.directional.mode),
                       "How directional lights are shadowed: `cascades` in the directional atlas (the keys below), "
                       "`virtual`: a virtual shadow map per light, a clipmap centred on the camera whose pages are "
                       "drawn only where visible surfaces need them, at the level whose texel matches the pixel's "
                       "footprint, and kept across frames until a light or a caster in them changes (the "
                       "`shadows.virtual` keys), or `auto`: virtual on a GPU, cascades on a CPU device."));
    t.push_back(atlasSizeKey("shadows.directional.atlasSize", PENUMBRA_FIELD(shadows.directional.atlasSize),
                             "directional shadow atlas, shared by up to 4 shadowed directional lights times "
                             "`cascadeCount` cascades."));
    t.push_back(filterKey("shadows.directional.filter", PENUMBRA_FIELD(shadows.directional.filter), "directional lights"));
    t.push_back(ranged("shadows.directional.cascadeCount", SettingType::Integer, 1, 4, "1..4",
                       PENUMBRA_FIELD(shadows.directional.cascadeCount), "Cascades per directional light."));
    t.push_back(ranged(
        "shadows.directional.cascadeRatios", SettingType::Ratios, 0.0, 1.0, "0..1",
        [](const Settings& s, size_t i) { return double(s.shadows.directional.cascadeRatios.at(i)); },
        [](Settings& s, size_t i, double v) { s.shadows.directional.cascadeRatios.at(i) = float(v); },
        "With `cascadeSplits: \"manual\"`: where the first three cascades end, as shares of the shadow "
        "distance; they must not decrease."));
    t.push_back(ranged("shadows.directional.cascadeFade", SettingType::Number, 0.001, 1.0, "0.001..1",
                       PENUMBRA_FIELD(shadows.directional.cascadeFade),
                       "The share at the end of each cascade over which it blends into the next (`cascadeBlend`) and "
                       "the last cascade fades out."));
    t.push_back(choice("shadows.directional.cascadeBlend", {"hard", "soft", "dither"},
                       PENUMBRA_FIELD(shadows.directional.cascadeBlend),
                       "How one cascade gives way to the next: `hard` switches, `soft` mixes the two cascades' samples, "
                       "`dither` picks one of the two per pixel by interleaved gradient noise."));
    t.push_back(choice("shadows.directional.fit", {"sphere", "tight"}, PENUMBRA_FIELD(shadows.directional.fit),
                       "How cascades are fitted: `sphere` around each slice's culling sphere (stable under camera "
                       "rotation), `tight` to the surfaces the frame shows (a reduction of the view's depth: the visible "
                       "depth range and each slice's light-space bounds, snapped to whole texels)."));
    t.push_back(choice("shadows.directional.cascadeSplits", {"manual", "log", "practical"},
                       PENUMBRA_FIELD(shadows.directional.cascadeSplits),
                       "Where cascades split: `manual` at `cascadeRatios`, `log` logarithmically over the depth range, "
                       "`practical` at `splitLambda` x log + (1 - `splitLambda`) x uniform."));
    t.push_back(ranged("shadows.directional.splitLambda", SettingType::Number, 0.0, 1.0, "0..1",
                       PENUMBRA_FIELD(shadows.directional.splitLambda),
                       "With `cascadeSplits: \"practical\"`: the weight of the logarithmic split."));
    t.push_back(flag("shadows.directional.receiverCulling", PENUMBRA_FIELD(shadows.directional.receiverCulling),
                     "Cascades leave out casters whose shadow cannot reach a surface that samples them: one inside the "
                     "camera's frustum and the cascade's depth range (tight fit) or culling sphere (sphere fit), within "
                     "the filter's reach. The image is the same; off draws every caster that meets a cascade's box."));
    t.push_back(choice("shadows.spot.mode", {"atlas", "virtual", "auto"}, PENUMBRA_FIELD(shadows.spot.mode),
                       "How spot and point lights are shadowed: `atlas` in tiles of the spot atlas (the keys below), or "
                       "`virtual`: a virtual shadow map per spot light and six per point light (one per cube face), "
                       "each a chain of mips whose pages are drawn only where visible surfaces need them, at the mip "
                       "whose texel matches the pixel's footprint, and kept across frames until the light or a caster "
                       "in them changes (`shadows.virtual.faceResolution`, `faceLodBias`, `pageSize`, `facePoolPages`), or `auto`: "
                       "virtual on a GPU, the atlas on a CPU device."));
    t.push_back(atlasSizeKey("shadows.spot.atlasSize", PENUMBRA_FIELD(shadows.spot.atlasSize),
                             "atlas of spot and point light shadows: up to 16 tiles, one per spot light and six per "
                             "point light."));
    t.push_back(filterKey("shadows.spot.filter", PENUMBRA_FIELD(shadows.spot.filter), "spot and point lights"));
    t.push_back(ranged("shadows.spot.depthBias", SettingType::Number, 0.0, 1.0, "0..1", PENUMBRA_FIELD(shadows.spot.depthBias),
                       "An extra constant clip-space depth bias of spot and point shadow maps, on top of `shadows.bias`."));
    t.push_back(ranged("shadows.virtual.pageSize", SettingType::PowerOfTwo, 64, 512, "a power of two in 64..512",
                       PENUMBRA_FIELD(shadows.virtualMaps.pageSize),
                       "Virtual shadow maps: texels along a page's side; pages are drawn, cached and evicted whole. "
                       "`resolution / pageSize` pages a level's side must be 8..256."));
    t.push_back(ranged("shadows.virtual.resolution", SettingType::PowerOfTwo, 1024, 32768, "a power of two in 1024..32768",
                       PENUMBRA_FIELD(shadows.virtualMaps.resolution),
                       "Virtual shadow maps: virtual texels along a clipmap level's side."));
    t.push_back(ranged("shadows.virtual.poolPages", SettingType::Integer, 16, 16384, "16..16384",
                       PENUMBRA_FIELD(shadows.virtualMaps.poolPages),
                       "Virtual shadow maps: physical pages per directional light, rounded down to a square number, "
                       "each pageSize^2 16-bit depth codes of the page's own depth range in one R16_UNORM image: 7056 "
                       "pages of 128^2 take 220.5 MiB (twice that on devices without R16_UNORM storage images), and the rasterizer draws a frame's pages into a target of at most 484 "
                       "32-bit pages (31 MiB). A 1920x1080 view needs about 700 pages per light at lodBias 0, "
                       "2000-3100 at -1, 4000-6000 at -1.5. When the visible pages need "
                       "more, a coarser level serves the rest (a warning and the stat `overflowed`); a pool larger "
                       "than the device holds is shrunk, with a warning."));
    t.push_back(ranged("shadows.virtual.facePoolPages", SettingType::Integer, 16, 16384, "16..16384",
                       PENUMBRA_FIELD(shadows.virtualMaps.facePoolPages),
                       "Virtual shadow maps of spot and point lights: physical pages for all their faces together, "
                       "rounded down to a square number, as `poolPages`. When the faces' visible pages need more, a "
                       "coarser mip serves the rest (a warning and the stat `overflowed`) and the frames after it "
                       "read mips one step coarser (up to two: pool pressure)."));
    t.push_back(ranged("shadows.virtual.levelCount", SettingType::Integer, 1, 16, "1..16",
                       PENUMBRA_FIELD(shadows.virtualMaps.levelCount),
                       "Virtual shadow maps: clipmap levels; level i is firstLevelSize x 2^i wide. Receivers beyond the "
                       "last level's window are unshadowed."));
    t.push_back(ranged("shadows.virtual.firstLevelSize", SettingType::Number, 0.125, 1048576.0, "0.125..1048576",
                       PENUMBRA_FIELD(shadows.virtualMaps.firstLevelSize),
                       "Virtual shadow maps: the finest level's side in scene units."));
    t.push_back(ranged("shadows.virtual.lodBias", SettingType::Number, -4.0, 4.0, "-4..4",
                       PENUMBRA_FIELD(shadows.virtualMaps.lodBias),
                       "Virtual shadow maps: which level a pixel reads, relative to the one whose texel matches the "
                       "pixel's footprint: -1 reads texels half as wide (four times the pages), +1 twice as wide. The default -1.5 "
                       "shimmers a third less than -1 for twice the pages (about 700 a 1920x1080 frame of a field, "
                       "4900 the CAD model's close-up)."));
    t.push_back(ranged("shadows.virtual.movingLodBias", SettingType::Number, -4.0, 4.0, "-4..4",
                       PENUMBRA_FIELD(shadows.virtualMaps.movingLodBias),
                       "Virtual shadow maps: the `lodBias` of a directional light whose direction changed in one of "
                       "its last 4 frames; 4 frames after it stops, it reads at `lodBias` again. Such a light's pages "
                       "are all drawn again every frame: at the default -1 (half the pages of `lodBias`'s -1.5) a sun that "
                       "turns every frame keeps the cost of -1. One-shot renders use `lodBias`."));
    t.push_back(flag("shadows.virtual.cache", PENUMBRA_FIELD(shadows.virtualMaps.cache),
                       "Virtual shadow maps: a drawn page stays valid across frames until its light, the scene's bounds "
                       "or a caster over it changes; off, every needed page is drawn again every frame."));
    t.push_back(ranged("shadows.virtual.keepFrames", SettingType::Integer, 0, 32, "0..32",
                       PENUMBRA_FIELD(shadows.virtualMaps.keepFrames),
                       "Virtual shadow maps: frames a page nobody requests stays resident (and reusable without a "
                       "redraw) before the pool may give it to another page."));
    t.push_back(ranged("shadows.virtual.pagesPerFrame", SettingType::Integer, 0, 65536, "0..65536",
                       PENUMBRA_FIELD(shadows.virtualMaps.pagesPerFrame),
                       "Virtual shadow maps: the most pages one frame draws per directional light (and for all the spot "
                       "and point light faces together); the rest wait for the next frames, coarse levels first, a "
                       "coarser level serving their pixels meanwhile (the stat `deferred`). 0: as many as the page "
                       "raster's culling lists hold, every page unless the scene has so many instances that they "
                       "would take more than 256 MiB or the device's storage buffers (a list has room for every "
                       "instance: 65 pages a frame at a million; the stat `pagesPerFrame`). A lower value bounds the "
                       "cost of a frame that finds many pages dirty (a camera cut, a light turned once); where every "
                       "frame dirties them all (`cache` off, a light turning every frame) the pages past it are not "
                       "drawn while that lasts."));
    t.push_back(ranged("shadows.virtual.faceResolution", SettingType::PowerOfTwo, 1024, 16384,
                       "a power of two in 1024..16384", PENUMBRA_FIELD(shadows.virtualMaps.faceResolution),
                       "Virtual shadow maps of spot and point lights (`shadows.spot.mode = virtual`): virtual texels "
                       "along the side of a face's finest mip (a spot light's cone, a point light's cube face); "
                       "`faceResolution / pageSize` must be 2..128 pages."));
    t.push_back(ranged("shadows.virtual.faceLodBias", SettingType::Number, -4.0, 4.0, "-4..4",
                       PENUMBRA_FIELD(shadows.virtualMaps.faceLodBias),
                       "Virtual shadow maps of spot and point lights: which mip a pixel reads, relative to the one "
                       "whose texel matches the pixel's footprint (as `lodBias` for the clipmaps)."));
    SettingKey exposure = ranged("render.exposure", SettingType::Number, 0.0, kHuge, "> 0", PENUMBRA_FIELD(render.exposure),
                                 "Scales linear radiance before tone mapping and sRGB encoding.");
    exposure.minExclusive = true;
    t.push_back(exposure);
    t.push_back(ranged("render.ambient", SettingType::Number, 0.0, 1.0, "0..1", PENUMBRA_FIELD(render.ambient),
                       "An unshadowed sky light: the background gradient's irradiance (a hemisphere light fitted to it, "
                       "`shaders/sky_light.glsl`) times the base colour, scaled by this; 0 turns it off. "
                       "The shadow and cascades AOVs never include it."));
    t.push_back(choice("render.lightCulling", {"clustered", "none"}, PENUMBRA_FIELD(render.lightCulling),
                       "How the lit pass finds a pixel's spot and point lights: `clustered` loops over the lights of the "
                       "pixel's view-space cluster only, `none` over every light. The image is the same."));
    t.push_back(choice("render.viewCulling", {"occlusion", "frustum", "none"}, PENUMBRA_FIELD(render.viewCulling),
                       "How the visibility-buffer main view culls its instances on the GPU: `frustum` against the camera "
                       "frustum, `occlusion` also against a depth pyramid in two phases, `none` not at all. The image is "
                       "the same; the forward pass draws every instance."));
    t.push_back(flag("render.meshletCulling", PENUMBRA_FIELD(render.meshletCulling),
                       "The compute rasterizers skip meshlets outside the view or the shadow tile, shadow meshlets "
                       "that lie between the tile's texel centres, and main-view meshlets that face away from the "
                       "camera. The image is the same."));
    t.push_back(choice("render.mainView", {"forward", "visibility", "auto"}, PENUMBRA_FIELD(render.mainView),
                       "How the main view is drawn: `forward` by the graphics pipeline, `visibility` through a compute "
                       "visibility buffer (needs 64-bit buffer atomics), `auto` by a table on datacenter NVIDIA GPUs "
                       "(visibility) and elsewhere by whichever the first frames measure faster; on a CPU device `auto` "
                       "draws forward."));
    t.push_back(choice("render.toneMapping", {"none", "neutral", "aces"}, PENUMBRA_FIELD(render.toneMapping),
                       "How exposed radiance becomes display values: `neutral` is Khronos PBR Neutral, `aces` "
                       "Narkowicz's fit of the ACES filmic curve, `none` the linear values clamped to 1. The shadow and "
                       "cascade AOVs are never tone mapped."));
    t.push_back(choice("render.background", {"gradient", "black"}, PENUMBRA_FIELD(render.background),
                       "What the colour image shows where no surface is: a sky gradient by view direction (exposed and "
                       "tone mapped like the scene), or black."));
    return t;
}

#undef PENUMBRA_FIELD

std::string formatValue(const SettingKey& key, double value) {
    if (key.type == SettingType::Integer || key.type == SettingType::PowerOfTwo || key.type == SettingType::Choice)
        return std::to_string(int64_t(value));
    std::ostringstream out;
    out << float(value);
    return out.str();
}

// A float as the shortest decimal that reads back as the same float ("0.1", not 0.10000000149).
nlohmann::json shortestFloat(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, float(value));
    *result.ptr = '\0';
    return std::strtod(text, nullptr);
}

}  // namespace

const std::vector<SettingKey>& settingKeys() {
    static const std::vector<SettingKey> table = makeTable();
    return table;
}

const SettingKey* findSettingKey(const std::string& key) {
    for (const SettingKey& setting : settingKeys())
        if (key == setting.key) return &setting;
    return nullptr;
}

bool settingValueAllowed(const SettingKey& key, double value) {
    if (!std::isfinite(value) || value > key.max || value < key.min || (key.minExclusive && value <= key.min)) return false;
    if (key.type == SettingType::Number || key.type == SettingType::Ratios) return true;
    if (value != std::floor(value)) return false;
    if (key.type == SettingType::PowerOfTwo) {
        const uint64_t n = uint64_t(value);
        return n != 0 && (n & (n - 1)) == 0;
    }
    return true;
}

// Validation of one group of keys ("shadows." or "render."): the first value out of its range, then the
// ratios' order.
void validateSettingKeys(const Settings& settings, std::string_view prefix) {
    for (const SettingKey& key : settingKeys()) {
        if (!std::string_view(key.key).starts_with(prefix)) continue;  // no allocation: runs every frame
        for (size_t i = 0; i < key.elements(); ++i) {
            const double value = key.get(settings, i);
            if (settingValueAllowed(key, value)) continue;
            const std::string name = key.type == SettingType::Ratios ? std::string(key.key) + "[" + std::to_string(i) + "]" : key.key;
            const std::string allowed = key.type == SettingType::Choice ? "a known enumerator" : key.allowed;
            throw Error("settings: " + name + " = " + formatValue(key, value) + " is out of range (allowed " + allowed + ")");
        }
    }
    // Decreasing ratios would make a cascade end before it starts (Catlike Coding "Directional Shadows"
    // leaves them to the user); an error, not a silent sort, so the user sees which split they asked for.
    const auto& ratios = settings.shadows.directional.cascadeRatios;
    if (prefix == "shadows." && (ratios[1] < ratios[0] || ratios[2] < ratios[1])) {
        std::ostringstream text;
        text << "[" << ratios[0] << ", " << ratios[1] << ", " << ratios[2] << "]";
        throw Error("settings: shadows.directional.cascadeRatios = " + text.str() + " must not decrease");
    }
    const VirtualShadowSettings& pages = settings.shadows.virtualMaps;
    const uint32_t pagesPerSide = pages.resolution / std::max(pages.pageSize, 1u);
    if (prefix == "shadows." && (pagesPerSide < 8 || pagesPerSide > 256))
        throw Error("settings: shadows.virtual.resolution / shadows.virtual.pageSize = " + std::to_string(pages.resolution) +
                    " / " + std::to_string(pages.pageSize) + " = " + std::to_string(pagesPerSide) +
                    " pages a side is out of range (allowed 8..256)");
    const uint32_t facePages = pages.faceResolution / std::max(pages.pageSize, 1u);
    if (prefix == "shadows." && (facePages < 2 || facePages > 128))
        throw Error("settings: shadows.virtual.faceResolution / shadows.virtual.pageSize = " +
                    std::to_string(pages.faceResolution) + " / " + std::to_string(pages.pageSize) + " = " +
                    std::to_string(facePages) + " pages a side is out of range (allowed 2..128)");
}

void validateShadowSettings(const ShadowSettings& shadows) {
    Settings settings;
    settings.shadows = shadows;
    validateSettingKeys(settings, "shadows.");
}

void validateSettings(const Settings& settings) {
    validateSettingKeys(settings, "shadows.");
    validateSettingKeys(settings, "render.");
}

std::string settingsToJson(const Settings& settings) {
    nlohmann::json root = nlohmann::json::object();
    for (const SettingKey& key : settingKeys()) {
        nlohmann::json value;
        switch (key.type) {
            case SettingType::Number: value = shortestFloat(key.get(settings, 0)); break;
            case SettingType::Integer:
            case SettingType::PowerOfTwo: value = uint32_t(key.get(settings, 0)); break;
            case SettingType::Bool: value = key.get(settings, 0) != 0.0; break;
            case SettingType::Choice: value = key.choices.at(size_t(key.get(settings, 0))); break;
            case SettingType::Ratios:
                value = nlohmann::json::array();
                for (size_t i = 0; i < 3; ++i) value.push_back(shortestFloat(key.get(settings, i)));
                break;
        }
        root[nlohmann::json::json_pointer("/" + [&] {
            std::string path = key.key;
            for (char& c : path)
                if (c == '.') c = '/';
            return path;
        }())] = value;
    }
    return root.dump(2);
}

}  // namespace penumbra
