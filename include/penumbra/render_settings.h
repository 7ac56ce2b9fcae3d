#pragma once
// Non-shadow render settings (the "render" block of the settings JSON, docs/settings.md).
#include <optional>
#include <string>

namespace penumbra {

// How the lit pass finds the spot and point lights of a pixel: Clustered loops over the
// lights of the pixel's view-space cluster only (the same image); None loops over every light.
enum class LightCulling { Clustered, None };
const char* lightCullingName(LightCulling culling);
std::optional<LightCulling> parseLightCulling(const std::string& name);

// How the main view is drawn: Forward rasterizes and shades every draw in the graphics
// pipeline; Visibility rasterizes opaque and alpha-tested triangles in compute into a visibility
// buffer and shades each pixel once in a compute resolve (the same shading functions, the same image
// within 2 levels), with blended materials drawn forward afterwards; Auto picks Visibility where the
// device has 64-bit buffer atomics and the scene's ids fit, Forward otherwise.
enum class MainView { Forward, Visibility, Auto };
const char* mainViewName(MainView view);
std::optional<MainView> parseMainView(const std::string& name);
// How the visibility-buffer main view culls its instances on the GPU: Occlusion tests
// the camera frustum and, in two phases, a depth pyramid of what was drawn first (last frame's
// visible set); Frustum the frustum only; None draws every opaque and alpha-tested instance. The
// image is the same (every instance a pixel shows is drawn); the forward pass ignores it. Default
// Frustum: on the H200's field scenes almost nothing is hidden per instance and the second phase
// costs 0.19 ms (docs/performance.md); Occlusion pays off where large occluders hide many instances.
enum class ViewCulling { Occlusion, Frustum, None };
const char* viewCullingName(ViewCulling culling);
std::optional<ViewCulling> parseViewCulling(const std::string& name);

// The display transform applied to linear radiance (x exposure) before sRGB encoding:
// Neutral = Khronos PBR Neutral (base colours stay close to their sRGB values, highlights roll off
// to white), Aces = Narkowicz's fit of the ACES filmic curve, None = clamp only (the linear values).
// The shadow and cascade AOVs are never tone mapped.
enum class ToneMapping { None, Neutral, Aces };
const char* toneMappingName(ToneMapping toneMapping);
std::optional<ToneMapping> parseToneMapping(const std::string& name);

// What the colour image shows where no geometry is: Gradient = a sky gradient by view direction
// (zenith, horizon, ground; exposed and tone mapped like the scene), Black = black. The AOVs keep
// their backgrounds (shadow: 1, cascades: black).
enum class Background { Gradient, Black };
const char* backgroundName(Background background);
std::optional<Background> parseBackground(const std::string& name);

struct RenderSettings {
    float exposure = 1.0f;  // linear scale applied before sRGB encoding
    // The ambient sky light: a hemisphere light with the background gradient's sky and ground
    // (shaders/sky_light.glsl), unshadowed, times base colour. 0 = no ambient light at all; 1 = the
    // sky as bright as the gradient the camera sees.
    float ambient = 0.5f;
    LightCulling lightCulling = LightCulling::Clustered;
    MainView mainView = MainView::Auto;
    ViewCulling viewCulling = ViewCulling::Frustum;  // occlusion measured slower where little is hidden (docs/performance.md)
    // The compute rasterizers (visibility buffer, compute shadow raster) skip whole meshlets outside
    // the view or shadow tile, and, in the main view, meshlets whose every triangle faces away from
    // the camera. The image is the same. Off by default: on the H200's field scenes it skips 3 % of
    // the main view's meshlets and almost none of the shadow tiles', and its tests cost more than that
    // saves (docs/performance.md).
    bool meshletCulling = false;
    ToneMapping toneMapping = ToneMapping::Neutral;
    Background background = Background::Gradient;
    bool operator==(const RenderSettings&) const = default;
};

}  // namespace penumbra
