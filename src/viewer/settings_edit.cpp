#include "viewer/settings_edit.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "penumbra/error.h"

namespace penumbra::viewer {

std::vector<double> inspectorValues(const SettingKey& key) {
    std::vector<double> values;
    switch (key.type) {
        case SettingType::Bool: values = {0.0, 1.0}; break;
        case SettingType::Choice:
            for (size_t i = 0; i < key.choices.size(); ++i) values.push_back(double(i));
            break;
        case SettingType::PowerOfTwo:
            for (double v = key.min; v <= key.max; v *= 2.0) values.push_back(v);
            break;
        case SettingType::Integer:
            for (double v = key.min; v <= key.max; v += 1.0) values.push_back(v);
            break;
        case SettingType::Number:
        case SettingType::Ratios:
            // An open lower end is offered just above it; an unbounded upper end as 1000 (a drag goes on).
            values = {key.minExclusive ? key.min + 0.001 : key.min, std::min(key.max, 1000.0)};
            break;
    }
    return values;
}

std::string applyInspectorEdit(Settings& settings, const SettingKey& key, size_t element, double value) {
    if (!settingValueAllowed(key, value))
        return std::string(key.key) + ": " + std::to_string(value) + " is out of range (allowed " + key.allowed + ")";
    Settings edited = settings;
    key.set(edited, element, value);
    if (key.type == SettingType::Ratios) {  // a ratio pushes its neighbours rather than cross them
        auto& ratios = edited.shadows.directional.cascadeRatios;
        for (size_t i = element + 1; i < ratios.size(); ++i) ratios[i] = std::max(ratios[i], ratios[i - 1]);
        for (size_t i = element; i-- > 0;) ratios[i] = std::min(ratios[i], ratios[i + 1]);
    }
    try {
        validateSettings(edited);
    } catch (const Error& error) {
        return error.what();
    }
    if (!edited.userSet(key.key)) edited.userKeys.push_back(key.key);
    settings = edited;
    return "";
}

std::string saveSettingsFile(const Settings& settings, const std::string& path) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << settingsToJson(settings) << "\n";
    file.close();
    return file ? "" : "cannot write " + path;
}

}  // namespace penumbra::viewer
