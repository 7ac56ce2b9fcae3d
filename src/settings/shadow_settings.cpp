#include "penumbra/shadow_settings.h"

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
constexpr const char* kViewCullingNames[] = {"occlusion", "frustum", "none"};
constexpr const char* kMainViewNames[] = {"forward", "visibility", "auto"};
constexpr const char* kToneMappingNames[] = {"none", "neutral", "aces"};
constexpr const char* kBackgroundNames[] = {"gradient", "black"};

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

}  // namespace

const char* shadowFilterName(ShadowFilter filter) { return enumName(kFilterNames, int(filter)); }
const char* cascadeBlendName(CascadeBlend blend) { return enumName(kBlendNames, int(blend)); }
const char* shadowBiasModeName(ShadowBiasMode mode) { return enumName(kBiasModeNames, int(mode)); }
const char* shadowFadeModeName(ShadowFadeMode mode) { return enumName(kFadeModeNames, int(mode)); }
std::optional<ShadowFadeMode> parseShadowFadeMode(const std::string& name) {
    return parseEnum<ShadowFadeMode>(kFadeModeNames, name);
}
const char* lightCullingName(LightCulling culling) { return enumName(kLightCullingNames, int(culling)); }
const char* mainViewName(MainView view) { return enumName(kMainViewNames, int(view)); }
std::optional<MainView> parseMainView(const std::string& name) { return parseEnum<MainView>(kMainViewNames, name); }
std::optional<LightCulling> parseLightCulling(const std::string& name) {
    return parseEnum<LightCulling>(kLightCullingNames, name);
}

const char* viewCullingName(ViewCulling culling) { return enumName(kViewCullingNames, int(culling)); }

std::optional<ViewCulling> parseViewCulling(const std::string& name) {
    return parseEnum<ViewCulling>(kViewCullingNames, name);
}
const char* toneMappingName(ToneMapping toneMapping) { return enumName(kToneMappingNames, int(toneMapping)); }
std::optional<ToneMapping> parseToneMapping(const std::string& name) {
    return parseEnum<ToneMapping>(kToneMappingNames, name);
}
const char* backgroundName(Background background) { return enumName(kBackgroundNames, int(background)); }
std::optional<Background> parseBackground(const std::string& name) { return parseEnum<Background>(kBackgroundNames, name); }
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

const char* directionalShadowModeName(DirectionalShadowMode mode) {
    return mode == DirectionalShadowMode::Virtual ? "virtual" : mode == DirectionalShadowMode::Auto ? "auto" : "cascades";
}

const char* spotShadowModeName(SpotShadowMode mode) {
    return mode == SpotShadowMode::Virtual ? "virtual" : mode == SpotShadowMode::Auto ? "auto" : "atlas";
}

// validateShadowSettings: src/settings/settings_keys.cpp, from the table of every key.

}  // namespace penumbra
