#include "shadows/shadow_settings.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace penumbra {

namespace {

constexpr const char* kFilterNames[] = {"PCF2x2", "PCF3x3", "PCF5x5", "PCF7x7"};
constexpr const char* kBlendNames[] = {"hard", "soft", "dither"};
constexpr const char* kBiasModeNames[] = {"normal", "scaledNormal", "receiverPlane"};

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

const char* shadowFilterName(ShadowFilter filter) {
    const int i = int(filter);
    return i >= 0 && i < 4 ? kFilterNames[i] : "?";
}

const char* cascadeBlendName(CascadeBlend blend) {
    const int i = int(blend);
    return i >= 0 && i < 3 ? kBlendNames[i] : "?";
}

const char* shadowBiasModeName(ShadowBiasMode mode) {
    const int i = int(mode);
    return i >= 0 && i < 3 ? kBiasModeNames[i] : "?";
}

std::optional<ShadowBiasMode> parseShadowBiasMode(const std::string& name) {
    for (int i = 0; i < 3; ++i) {
        if (name == kBiasModeNames[i]) return ShadowBiasMode(i);
    }
    return std::nullopt;
}

std::optional<ShadowFilter> parseShadowFilter(const std::string& name) {
    for (int i = 0; i < 4; ++i) {
        if (name == kFilterNames[i]) return ShadowFilter(i);
    }
    return std::nullopt;
}

std::optional<CascadeBlend> parseCascadeBlend(const std::string& name) {
    for (int i = 0; i < 3; ++i) {
        if (name == kBlendNames[i]) return CascadeBlend(i);
    }
    return std::nullopt;
}

void validateShadowSettings(const ShadowSettings& settings) {
    constexpr float kHuge = 3.0e38f;
    checkEnum("shadows.bias", int(settings.bias), 3);
    checkFloatRange("shadows.maxDistance", settings.maxDistance, 0.001f, kHuge, ">= 0.001");
    checkFloatRange("shadows.distanceFade", settings.distanceFade, 0.001f, 1.0f, "0.001..1");
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
    checkFloatRange("shadows.directional.cascadeFade", directional.cascadeFade, 0.001f, 1.0f, "0.001..1");
    checkEnum("shadows.directional.cascadeBlend", int(directional.cascadeBlend), 3);
    checkAtlasSize("shadows.spot.atlasSize", settings.spot.atlasSize);
    checkEnum("shadows.spot.filter", int(settings.spot.filter), 4);
    checkFloatRange("shadows.spot.depthBias", settings.spot.depthBias, 0.0f, 1.0f, "0..1");
}

}  // namespace penumbra
