// The table of every settings key (penumbra/settings_keys.h) and the validation it drives.
#include "penumbra/settings_keys.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
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
                  void (*set)(Settings&, size_t, double)) {
    SettingKey setting{key, SettingType::Choice, 0.0, double(names.size() - 1)};
    setting.allowed = joined(names);
    setting.choices = std::move(names);
    setting.get = get;
    setting.set = set;
    return setting;
}

SettingKey ranged(const char* key, SettingType type, double min, double max, const char* allowed,
                  double (*get)(const Settings&, size_t), void (*set)(Settings&, size_t, double)) {
    SettingKey setting{key, type, min, max};
    setting.allowed = allowed;
    setting.get = get;
    setting.set = set;
    return setting;
}

// The original pipeline-asset keys first, then those added since; validation reports the first bad one.
std::vector<SettingKey> makeTable() {
    std::vector<SettingKey> t;
    t.push_back(choice("shadows.bias", {"normal", "scaledNormal", "receiverPlane"}, PENUMBRA_FIELD(shadows.bias)));
    t.push_back(choice("shadows.fadeMode", {"linear", "squared"}, PENUMBRA_FIELD(shadows.fadeMode)));
    t.push_back(ranged("shadows.maxDistance", SettingType::Number, 0.001, kHuge, ">= 0.001", PENUMBRA_FIELD(shadows.maxDistance)));
    t.push_back(ranged("shadows.distanceFade", SettingType::Number, 0.001, 1.0, "0.001..1", PENUMBRA_FIELD(shadows.distanceFade)));
    t.push_back(ranged("shadows.screenSpace", SettingType::Bool, 0, 1, "true, false", PENUMBRA_FIELD(shadows.screenSpace)));
    t.push_back(choice("shadows.raster", {"hw", "compute", "auto"}, PENUMBRA_FIELD(shadows.raster)));
    t.push_back(ranged("shadows.cacheTiles", SettingType::Bool, 0, 1, "true, false", PENUMBRA_FIELD(shadows.cacheTiles)));
    t.push_back(ranged("shadows.directional.atlasSize", SettingType::PowerOfTwo, 256, 8192, "a power of two in 256..8192",
                       PENUMBRA_FIELD(shadows.directional.atlasSize)));
    t.push_back(choice("shadows.directional.filter", kFilters, PENUMBRA_FIELD(shadows.directional.filter)));
    t.push_back(ranged("shadows.directional.cascadeCount", SettingType::Integer, 1, 4, "1..4",
                       PENUMBRA_FIELD(shadows.directional.cascadeCount)));
    t.push_back(ranged(
        "shadows.directional.cascadeRatios", SettingType::Ratios, 0.0, 1.0, "0..1",
        [](const Settings& s, size_t i) { return double(s.shadows.directional.cascadeRatios.at(i)); },
        [](Settings& s, size_t i, double v) { s.shadows.directional.cascadeRatios.at(i) = float(v); }));
    t.push_back(ranged("shadows.directional.cascadeFade", SettingType::Number, 0.001, 1.0, "0.001..1",
                       PENUMBRA_FIELD(shadows.directional.cascadeFade)));
    t.push_back(choice("shadows.directional.cascadeBlend", {"hard", "soft", "dither"},
                       PENUMBRA_FIELD(shadows.directional.cascadeBlend)));
    t.push_back(choice("shadows.directional.fit", {"sphere", "tight"}, PENUMBRA_FIELD(shadows.directional.fit)));
    t.push_back(choice("shadows.directional.cascadeSplits", {"manual", "log", "practical"},
                       PENUMBRA_FIELD(shadows.directional.cascadeSplits)));
    t.push_back(ranged("shadows.directional.splitLambda", SettingType::Number, 0.0, 1.0, "0..1",
                       PENUMBRA_FIELD(shadows.directional.splitLambda)));
    t.push_back(ranged("shadows.spot.atlasSize", SettingType::PowerOfTwo, 256, 8192, "a power of two in 256..8192",
                       PENUMBRA_FIELD(shadows.spot.atlasSize)));
    t.push_back(choice("shadows.spot.filter", kFilters, PENUMBRA_FIELD(shadows.spot.filter)));
    t.push_back(ranged("shadows.spot.depthBias", SettingType::Number, 0.0, 1.0, "0..1", PENUMBRA_FIELD(shadows.spot.depthBias)));
    SettingKey exposure = ranged("render.exposure", SettingType::Number, 0.0, kHuge, "> 0", PENUMBRA_FIELD(render.exposure));
    exposure.minExclusive = true;
    t.push_back(exposure);
    t.push_back(ranged("render.ambient", SettingType::Number, 0.0, 1.0, "0..1", PENUMBRA_FIELD(render.ambient)));
    t.push_back(choice("render.lightCulling", {"clustered", "none"}, PENUMBRA_FIELD(render.lightCulling)));
    t.push_back(choice("render.viewCulling", {"occlusion", "frustum", "none"}, PENUMBRA_FIELD(render.viewCulling)));
    t.push_back(ranged("render.meshletCulling", SettingType::Bool, 0, 1, "true, false", PENUMBRA_FIELD(render.meshletCulling)));
    t.push_back(choice("render.mainView", {"forward", "visibility", "auto"}, PENUMBRA_FIELD(render.mainView)));
    t.push_back(choice("render.toneMapping", {"none", "neutral", "aces"}, PENUMBRA_FIELD(render.toneMapping)));
    t.push_back(choice("render.background", {"gradient", "black"}, PENUMBRA_FIELD(render.background)));
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
void validateSettingKeys(const Settings& settings, const std::string& prefix) {
    for (const SettingKey& key : settingKeys()) {
        if (std::string(key.key).rfind(prefix, 0) != 0) continue;
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
