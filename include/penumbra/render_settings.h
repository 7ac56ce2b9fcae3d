#pragma once
// Non-shadow render settings (the "render" block of the settings JSON, an extension of DESIGN.md).
#include <optional>
#include <string>

namespace penumbra {

// How the lit pass finds the spot and point lights of a pixel (issue 11): Clustered loops over the
// lights of the pixel's view-space cluster only (the same image); None loops over every light.
enum class LightCulling { Clustered, None };
const char* lightCullingName(LightCulling culling);
std::optional<LightCulling> parseLightCulling(const std::string& name);

struct RenderSettings {
    float exposure = 1.0f;  // linear scale applied before sRGB encoding
    float ambient = 0.03f;  // constant ambient light, as a fraction of base colour
    LightCulling lightCulling = LightCulling::Clustered;
};

}  // namespace penumbra
