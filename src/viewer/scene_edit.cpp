#include "viewer/scene_edit.h"

#include "penumbra/error.h"

namespace penumbra::viewer {

std::vector<LightWidget> lightWidgets(LightType type) {
    const bool sun = type == LightType::Directional;
    return {
        {"strength", &Light::shadowStrength, 0.0f, 1.0f, 0.0f},
        {"slope bias", &Light::shadowBias, 0.0f, 10.0f, 0.01f},
        {"normal bias", &Light::shadowNormalBias, 0.0f, 10.0f, 0.01f},
        {"near plane", &Light::shadowNearPlane, 0.0f, 100.0f, 0.01f},
        {sun ? "light size (deg)" : "light radius (m)", &Light::shadowLightSize, 0.0f, sun ? 20.0f : 10.0f, 0.01f},
    };
}

std::string applySceneEdit(const std::function<void()>& edit) {
    try {
        edit();
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

}  // namespace penumbra::viewer
