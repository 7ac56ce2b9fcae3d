#pragma once
// All settings of one render: the pipeline asset of DESIGN.md ("shadows") plus "render".
#include <string>

#include <penumbra/render_settings.h>
#include <penumbra/shadow_settings.h>

namespace penumbra {

struct Settings {
    ShadowSettings shadows;
    RenderSettings render;
};

// Parses settings JSON text; every key optional. Unknown key, wrong type or out-of-range value:
// throws Error naming the key (dotted path) and the allowed range. `origin` names the source.
Settings parseSettingsJson(const std::string& jsonText, const std::string& origin);
Settings loadSettingsFile(const std::string& path);
// Applies one "dotted.key=value" override (the CLI's --set) with the same validation.
void applySettingOverride(Settings& settings, const std::string& assignment);
// Validates ranges (DESIGN.md); throws Error naming the first bad key.
void validateSettings(const Settings& settings);

}  // namespace penumbra
