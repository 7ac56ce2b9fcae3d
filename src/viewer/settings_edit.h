#pragma once
// What the settings inspector does with a value, without a window (so it is unit-tested): the
// values each key's widget offers, from the table of penumbra/settings_keys.h, and one edit applied
// with the same validation as a settings file.
#include <string>
#include <vector>

#include "penumbra/settings.h"
#include "penumbra/settings_keys.h"

namespace penumbra::viewer {

// The values a widget of `key` offers: every choice, power of two or integer of the range; for a
// number or ratio its two ends (a slider in between).
std::vector<double> inspectorValues(const SettingKey& key);
// Sets element `element` of `key` to `value` when validation accepts the result (the Ratios keep their
// order); otherwise leaves `settings` alone and returns the validation message.
std::string applyInspectorEdit(Settings& settings, const SettingKey& key, size_t element, double value);
// "Save settings": the JSON that penumbra render --settings reads, written to `path`; "" or the error.
std::string saveSettingsFile(const Settings& settings, const std::string& path);

}  // namespace penumbra::viewer
