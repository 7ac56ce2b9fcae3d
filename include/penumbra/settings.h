#pragma once
// All settings of one render: the "shadows" and "render" blocks of the settings JSON (docs/settings.md).
#include <string>
#include <vector>

#include <penumbra/render_settings.h>
#include <penumbra/shadow_settings.h>

namespace penumbra {

struct CameraView;
struct Scene;

struct Settings {
    ShadowSettings shadows;
    RenderSettings render;
    // The dotted keys a settings JSON or a --set override gave (filled by parseSettingsJson and
    // applySettingOverride), so that applySceneDefaults leaves the user's own choices alone.
    std::vector<std::string> userKeys;
    bool userSet(const std::string& key) const;
    bool operator==(const Settings&) const = default;
};

// Parses settings JSON text; every key optional. Unknown key, wrong type or out-of-range value:
// throws Error naming the key (dotted path) and the allowed range. `origin` names the source.
Settings parseSettingsJson(const std::string& jsonText, const std::string& origin);
Settings loadSettingsFile(const std::string& path);
// Applies one "dotted.key=value" override (the CLI's --set) with the same validation.
void applySettingOverride(Settings& settings, const std::string& assignment);
// Validates ranges (settings_keys.h); throws Error naming the first bad key.
void validateSettings(const Settings& settings);

// Defaults that depend on the scene, for keys not in settings.userKeys. Today one:
// shadows.maxDistance. Its default, 100, assumes a scene in metres with something within 100 m of
// the camera. When the whole scene (its bounds) lies farther than that (a model in millimetres seen
// whole, a scene 10^6 m across) or within 1 unit of the camera (a scene in kilometres), maxDistance
// becomes the distance to the scene's farthest corner (at most the camera's far plane), so the
// shadows cover what is in view. A scene with content near the camera keeps 100, as before.
// Returns one warning line per value it changed.
std::vector<std::string> applySceneDefaults(Settings& settings, const Scene& scene, const CameraView& view);

}  // namespace penumbra
