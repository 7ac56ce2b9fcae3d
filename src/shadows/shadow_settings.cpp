#include "penumbra/shadow_settings.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "penumbra/render_settings.h"

namespace penumbra {

namespace {

constexpr const char* kFilterNames[] = {"PCF2x2", "PCF3x3", "PCF5x5", "PCF7x7"};
constexpr const char* kBlendNames[] = {"hard", "soft", "dither"};
constexpr const char* kRasterNames[] = {"hw", "compute", "auto"};
constexpr const char* kBiasModeNames[] = {"normal", "scaledNormal", "receiverPlane"};
constexpr const char* kFitNames[] = {"sphere", "tight"};
constexpr const char* kFadeModeNames[] = {"linear", "squared"};
constexpr const char* kSplitModeNames[] = {"manual", "log", "practical"};
constexpr const char* kLightCullingNames[] = {"clustered", "none"};

// The name of enumerator `value` in `names`, "?" when out of range; and back.
template <size_t N>
const char* enumName(const char* const (&names)[N], int value) {
    return value >= 0 && value < int(N) ? names[value] : "?";
}
template <typename E, size_t N>
std::optional<E> parseEnum(const char* const (&names)[N], const std::string& name) {
    for (size_t i = 0; i < N; ++i) {
        if (name == names[i]) return E(i);
    }
    return std::nullopt;
}

std::string formatValue(float value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

[[noreturn]] void throwOutOfRange(const std::string& key, const std::string& value, const std::string& allowed) {
    throw Error("settings: " + key + " = " + value + " is out of range (allowed " + allowed + ")");
}

// Ranges as the seed's inspector attributes give them: [Min(0.001f)] maxDistance, [Range(0.001f, 1f)]
// fades (seed 000 §3.7, §3.8), [Range(1, 4)] cascadeCount and [Range(0f, 1f)] ratios (seed 000 §3.1).
void checkFloatRange(const std::string& key, float value, float lo, float hi, const std::string& allowed) {
    if (!std::isfinite(value) || value < lo || value > hi) throwOutOfRange(key, formatValue(value), allowed);
}

void checkAtlasSize(const std::string& key, uint32_t size) {
    const bool powerOfTwo = size != 0 && (size & (size - 1)) == 0;
    if (!powerOfTwo || size < 256 || size > 8192) {
        throwOutOfRange(key, std::to_string(size), "a power of two in 256..8192");
    }
}

void checkEnum(const std::string& key, int value, int count) {
    if (value < 0 || value >= count) throwOutOfRange(key, std::to_string(value), "a known enumerator");
}

}  // namespace

const char* shadowFilterName(ShadowFilter filter) { return enumName(kFilterNames, int(filter)); }
const char* cascadeBlendName(CascadeBlend blend) { return enumName(kBlendNames, int(blend)); }
const char* shadowBiasModeName(ShadowBiasMode mode) { return enumName(kBiasModeNames, int(mode)); }
const char* shadowFadeModeName(ShadowFadeMode mode) { return enumName(kFadeModeNames, int(mode)); }
std::optional<ShadowFadeMode> parseShadowFadeMode(const std::string& name) {
    return parseEnum<ShadowFadeMode>(kFadeModeNames, name);
}
const char* lightCullingName(LightCulling culling) { return enumName(kLightCullingNames, int(culling)); }
std::optional<LightCulling> parseLightCulling(const std::string& name) {
    return parseEnum<LightCulling>(kLightCullingNames, name);
}
const char* cascadeFitName(CascadeFit fit) { return enumName(kFitNames, int(fit)); }
const char* cascadeSplitModeName(CascadeSplitMode mode) { return enumName(kSplitModeNames, int(mode)); }

std::optional<ShadowFilter> parseShadowFilter(const std::string& name) { return parseEnum<ShadowFilter>(kFilterNames, name); }
std::optional<CascadeBlend> parseCascadeBlend(const std::string& name) { return parseEnum<CascadeBlend>(kBlendNames, name); }
std::optional<ShadowBiasMode> parseShadowBiasMode(const std::string& name) {
    return parseEnum<ShadowBiasMode>(kBiasModeNames, name);
}
std::optional<CascadeFit> parseCascadeFit(const std::string& name) { return parseEnum<CascadeFit>(kFitNames, name); }
std::optional<CascadeSplitMode> parseCascadeSplitMode(const std::string& name) {
    return parseEnum<CascadeSplitMode>(kSplitModeNames, name);
}

const char* shadowRasterName(ShadowRaster raster) {
    const int i = int(raster);
    return i >= 0 && i < 3 ? kRasterNames[i] : "?";
}

std::optional<ShadowRaster> parseShadowRaster(const std::string& name) {
    for (int i = 0; i < 3; ++i) {
        if (name == kRasterNames[i]) return ShadowRaster(i);
    }
    return std::nullopt;
}

void validateShadowSettings(const ShadowSettings& settings) {
    constexpr float kHuge = 3.0e38f;
    checkEnum("shadows.bias", int(settings.bias), 3);
    checkEnum("shadows.fadeMode", int(settings.fadeMode), 2);
    checkFloatRange("shadows.maxDistance", settings.maxDistance, 0.001f, kHuge, ">= 0.001");
    checkFloatRange("shadows.distanceFade", settings.distanceFade, 0.001f, 1.0f, "0.001..1");
    checkEnum("shadows.raster", int(settings.raster), 3);
    const DirectionalShadowSettings& directional = settings.directional;
    checkAtlasSize("shadows.directional.atlasSize", directional.atlasSize);
    checkEnum("shadows.directional.filter", int(directional.filter), 4);
    if (directional.cascadeCount < 1 || directional.cascadeCount > 4) {
        throwOutOfRange("shadows.directional.cascadeCount", std::to_string(directional.cascadeCount), "1..4");
    }
    for (size_t i = 0; i < directional.cascadeRatios.size(); ++i) {
        checkFloatRange("shadows.directional.cascadeRatios[" + std::to_string(i) + "]",
                        directional.cascadeRatios[i], 0.0f, 1.0f, "0..1");
    }
    // Decreasing ratios would make a cascade end before it starts (seed 000 §3.1 leaves them to the
    // user); an error, not a silent sort, so the user sees which split they asked for.
    const auto& ratios = directional.cascadeRatios;
    if (ratios[1] < ratios[0] || ratios[2] < ratios[1])
        throw Error("settings: shadows.directional.cascadeRatios = [" + formatValue(ratios[0]) + ", " +
                    formatValue(ratios[1]) + ", " + formatValue(ratios[2]) + "] must not decrease");
    checkFloatRange("shadows.directional.cascadeFade", directional.cascadeFade, 0.001f, 1.0f, "0.001..1");
    checkEnum("shadows.directional.cascadeBlend", int(directional.cascadeBlend), 3);
    checkEnum("shadows.directional.fit", int(directional.fit), 2);
    checkEnum("shadows.directional.cascadeSplits", int(directional.cascadeSplits), 3);
    checkFloatRange("shadows.directional.splitLambda", directional.splitLambda, 0.0f, 1.0f, "0..1");
    checkAtlasSize("shadows.spot.atlasSize", settings.spot.atlasSize);
    checkEnum("shadows.spot.filter", int(settings.spot.filter), 4);
    checkFloatRange("shadows.spot.depthBias", settings.spot.depthBias, 0.0f, 1.0f, "0..1");
}

}  // namespace penumbra
