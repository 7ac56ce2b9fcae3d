#pragma once
// Non-shadow render settings (the "render" block of the settings JSON, an extension of DESIGN.md).

namespace penumbra {

struct RenderSettings {
    float exposure = 1.0f;  // linear scale applied before sRGB encoding
    float ambient = 0.03f;  // constant ambient light, as a fraction of base colour
};

}  // namespace penumbra
