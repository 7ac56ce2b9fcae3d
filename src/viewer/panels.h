#pragma once
// The viewer's Dear ImGui panels: the view and camera, the stats of the frames the GPU finished, the
// settings inspector (inspector.cpp) and the scene inspector (lights, materials, nodes), and the
// atlas overlay's tile labels.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/renderer.h"
#include "penumbra/settings.h"
#include "viewer/atlas_overlay.h"
#include "viewer/camera_controller.h"
#include "viewer/cascade_frusta.h"
#include "viewer/reference_view.h"

namespace penumbra::viewer {

struct ViewerState;
class SceneDocument;

struct PanelContext {
    ViewerState& state;
    Settings& settings;  // what the next frame renders with
    Renderer& renderer;  // scene edits go through its setters
    CameraController& camera;
    const std::string& deviceName;
    SceneDocument& document;  // File > Open, Reload, Save scene go to it
};

void drawPanels(PanelContext& context);
// Moves `camera` to the scene's camera (index -1) or glTF camera `index` of `scene` (C, the camera combo).
void selectSceneCamera(ViewerState& state, CameraController& camera, const Scene& scene, int index);
// One red line at the bottom of the window (a scene that did not load), drawn with or without panels.
void drawErrorLine(const std::string& message);
// The frusta view's lines over the image of `view`: boxes and spheres in the cascade's colour
// (cascadeLineColor), the observed camera's frustum white.
void drawWorldLines(const std::vector<WorldLine>& lines, const CameraView& view);
// Cascade 0..3: red, green, blue, yellow (the cascades view's hues, saturated to stand out).
uint32_t cascadeLineColor(uint32_t cascade);
void drawStatsPanel(PanelContext& context);
// The split screen's labels at the top of each half: "current settings" and the second settings' file.
void drawSplitLabels(const std::string& compareSettingsPath);
// The reference view's window: until a comparison is shown, its button (true when pressed), its
// progress bar or its error; over a finished picture (with the panels) the metrics and the colours' key.
bool drawReferencePanel(ReferenceComparison& comparison, bool showPanels);
// The settings inspector: one widget per key of settingKeys() (penumbra/settings_keys.h).
void drawSettingsInspector(PanelContext& context);
void drawSceneInspector(PanelContext& context);
// Labels over the overlay at `windowRect` (x0, y0, x1, y1) of an atlas image of `atlasSize` pixels.
void drawAtlasLabels(const std::vector<AtlasTileLabel>& labels, const glm::vec4& windowRect, const glm::vec2& atlasSize);

}  // namespace penumbra::viewer
