#pragma once
// Every key of the settings JSON in one table: its type, its allowed range, what it does and the field
// of Settings it sets. The JSON and --set parser, validation, settingsToJson, penumbra-viewer's
// inspector and the settings reference (`penumbra settings --markdown`, docs/settings.md) all read this
// table, so the ranges an inspector offers are the ranges validation accepts and the ones documented.
#include <cstddef>
#include <string>
#include <vector>

#include <penumbra/settings.h>

namespace penumbra {

enum class SettingType {
    Number,      // a float in [min, max] (minExclusive: (min, max])
    Integer,     // an unsigned integer in [min, max]
    PowerOfTwo,  // an unsigned power of two in [min, max]
    Bool,
    Choice,      // one of `choices` (the enumerator with that index)
    Ratios,      // 3 floats, each in [min, max], not decreasing (cascade ratios)
};

struct SettingKey {
    const char* key;  // dotted path, e.g. "shadows.directional.cascadeCount"
    SettingType type;
    double min = 0.0, max = 0.0;
    bool minExclusive = false;
    std::vector<std::string> choices;  // Choice: names in enumerator order
    std::string allowed;               // the range as messages give it: "1..4", "hard, soft, dither"
    std::string description;           // what the key does, one paragraph (docs/settings.md is made from it)
    // The value of element `i` (0, or 0..2 for Ratios) as a number: floats and integers as they are,
    // Bool 0 / 1, Choice the enumerator's index.
    double (*get)(const Settings&, size_t i) = nullptr;
    void (*set)(Settings&, size_t i, double value) = nullptr;

    size_t elements() const { return type == SettingType::Ratios ? 3 : 1; }
};

const std::vector<SettingKey>& settingKeys();
const SettingKey* findSettingKey(const std::string& key);
// Whether `value` is allowed for one element of `key` (the Ratios' order is checked by validateSettings).
bool settingValueAllowed(const SettingKey& key, double value);
// Every key's value as settings JSON; parseSettingsJson of it gives the same values back.
std::string settingsToJson(const Settings& settings);
// The settings reference made from this table (docs/settings.md is its output: `penumbra settings
// --markdown`): every key with its type, allowed values, default and description, and the defaults as
// settings JSON, so that the documented keys, ranges and defaults are the ones validation uses.
std::string settingsReferenceMarkdown();

}  // namespace penumbra
