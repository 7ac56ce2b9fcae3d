#include "viewer/panels.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "viewer/panel_data.h"
#include "viewer/scene_document.h"
#include "viewer/viewer_app.h"

namespace penumbra::viewer {

namespace {

double totalGpuMs(const FrameStats& stats) {
    double total = 0.0;
    for (const PassTiming& timing : stats.gpuTimings)
        if (timing.name.find('/') == std::string::npos) total += timing.milliseconds;  // nested timers are inside
    return total;
}

// The scene's camera and each glTF camera by name; C steps through the same list.
void drawCameraCombo(PanelContext& c) {
    const Scene& scene = c.renderer.scene();
    const std::vector<std::string> choices = cameraChoices(scene);
    const int shown = c.state.sceneCamera < int(scene.cameras.size()) ? c.state.sceneCamera : -1;
    if (!ImGui::BeginCombo("camera (C)", choices[size_t(shown + 1)].c_str())) return;
    for (int i = -1; i + 1 < int(choices.size()); ++i) {
        ImGui::PushID(i);
        if (ImGui::Selectable(choices[size_t(i + 1)].c_str(), i == shown)) selectSceneCamera(c.state, c.camera, scene, i);
        ImGui::PopID();
    }
    ImGui::EndCombo();
}

void drawViewControls(PanelContext& c) {
    ViewerState& state = c.state;
    int view = int(state.view);
    const char* names[kViewModes];
    for (int i = 0; i < kViewModes; ++i) names[i] = viewModeName(ViewMode(i));
    ImGui::Combo("view", &view, names, kViewModes);
    state.view = ViewMode(view);
    const int lights = int(c.renderer.scene().lights.size());
    if (lights > 0) {
        int light = int(state.light);
        ImGui::SliderInt("light", &light, 0, lights - 1, "%d", ImGuiSliderFlags_AlwaysClamp);
        state.light = uint32_t(std::clamp(light, 0, lights - 1));
    }
    drawCameraCombo(c);
    bool orbit = c.camera.mode() == CameraMode::Orbit;
    if (ImGui::Checkbox("orbit camera", &orbit)) c.camera.setMode(orbit ? CameraMode::Orbit : CameraMode::Fly);
    ImGui::SameLine();
    if (ImGui::Button("frame scene (F)")) c.camera.frameScene();
    ImGui::Text("fly speed %.2f m/s (wheel)", c.camera.speed());
    const glm::vec3 p = c.camera.wsPosition();
    ImGui::Text("camera at (%.2f, %.2f, %.2f)", p.x, p.y, p.z);
}

// A path field and a button, the File menu's Open and Save scene.
bool pathField(const char* label, char* path, size_t size, const char* button) {
    ImGui::PushID(label);
    ImGui::SetNextItemWidth(260.0f);
    bool go = ImGui::InputText(label, path, size, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    go |= ImGui::Button(button);
    ImGui::PopID();
    return go && path[0] != '\0';
}

void drawFileMenu(ViewerState& state, SceneDocument& document) {
    if (!ImGui::BeginMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        ImGui::TextUnformatted("Open a .gltf / .glb (or drop one on the window):");
        if (pathField("##open", state.openPath, sizeof state.openPath, "Open")) {
            document.requestOpen(state.openPath);
            ImGui::CloseCurrentPopup();
        }
        if (ImGui::MenuItem("Reload", "R")) document.requestReload();
        ImGui::Separator();
        ImGui::TextUnformatted("Save the scene with its edited shadow extras (.gltf / .glb):");
        if (pathField("##save", state.sceneSavePath, sizeof state.sceneSavePath, "Save scene")) {
            document.requestSave(state.sceneSavePath);
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndMenu();
    }
    ImGui::EndMenuBar();
}

}  // namespace

void selectSceneCamera(ViewerState& state, CameraController& camera, const Scene& scene, int index) {
    state.sceneCamera = index;
    camera.reset(index < 0 ? startCamera(scene) : scene.cameras[size_t(index)]);
    state.status = index < 0 ? "the scene's camera"
                             : "glTF camera " + std::to_string(index) + " (" + cameraChoices(scene)[size_t(index + 1)] + ")";
}

void drawErrorLine(const std::string& message) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float height = ImGui::GetTextLineHeight();
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImVec2 min(0.0f, display.y - height - 8.0f);
    draw->AddRectFilled(min, display, IM_COL32(0, 0, 0, 200));
    draw->AddText(ImVec2(6.0f, min.y + 4.0f), IM_COL32(255, 40, 40, 255), message.c_str());
}

uint32_t cascadeLineColor(uint32_t cascade) {
    const uint32_t colors[4] = {IM_COL32(255, 0, 0, 255), IM_COL32(0, 255, 0, 255), IM_COL32(0, 90, 255, 255),
                                IM_COL32(255, 255, 0, 255)};
    return colors[cascade % 4];
}

void drawWorldLines(const std::vector<WorldLine>& lines, const CameraView& view) {
    ImDrawList* draw = ImGui::GetBackgroundDrawList();  // under the panels
    const glm::vec2 scale(ImGui::GetIO().DisplaySize.x / float(view.width), ImGui::GetIO().DisplaySize.y / float(view.height));
    for (const WorldLine& line : lines) {
        const auto pixels = projectToPixels(view, line.wsFrom, line.wsTo);
        if (!pixels) continue;
        const glm::vec2 a = pixels->first * scale, b = pixels->second * scale;
        const uint32_t color = line.kind == LineKind::ObservedFrustum ? IM_COL32(255, 255, 255, 255) : cascadeLineColor(line.cascade);
        draw->AddLine(ImVec2(a.x, a.y), ImVec2(b.x, b.y), color, line.kind == LineKind::Box ? 2.0f : 1.0f);
    }
}

void drawPanels(PanelContext& c) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 560), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Penumbra", nullptr, ImGuiWindowFlags_MenuBar)) {
        drawFileMenu(c.state, c.document);
        ImGui::TextWrapped("%s on %s", c.document.label().c_str(), c.deviceName.c_str());
        if (!c.state.status.empty()) ImGui::TextWrapped("%s", c.state.status.c_str());
        drawViewControls(c);
        if (ImGui::CollapsingHeader("Settings", ImGuiTreeNodeFlags_DefaultOpen)) drawSettingsInspector(c);
        if (ImGui::CollapsingHeader("Scene")) drawSceneInspector(c);
    }
    ImGui::End();
    drawStatsPanel(c);
}

// One map's pages per level (a clipmap's levels, the faces' mips): requested, of them cached (already
// resident) and drawn this frame; levels with nothing are left out.
static void drawLevelTable(const char* id, const char* column, const FrameStats::VirtualMapLevels& levels) {
    if (!ImGui::BeginTable(id, 4, ImGuiTableFlags_RowBg)) return;
    for (const char* heading : {column, "requested", "cached", "drawn"}) ImGui::TableSetupColumn(heading);
    ImGui::TableHeadersRow();
    for (uint32_t level = 0; level < levels.levelCount; ++level) {
        if (levels.requested[level] == 0 && levels.drawn[level] == 0) continue;  // outside the view
        ImGui::TableNextColumn();
        ImGui::Text("%u", level);
        for (uint32_t value : {levels.requested[level], levels.cached[level], levels.drawn[level]}) {
            ImGui::TableNextColumn();
            ImGui::Text("%u", value);
        }
    }
    ImGui::EndTable();
}

// The virtual shadow maps' page view: the frame's page counts and the pool's occupancy, then (folded) per
// map (directional light) and level, or for the spot and point lights' faces per mip. The cascades view
// (key 3) colours each pixel by the directional level it samples.
static void drawVirtualPageView(const FrameStats& last) {
    const auto counts = [](const char* what, const char* maps, const VirtualPageCounts& pages) {
        ImGui::Text("%s (%u %s): %u requested, %u cached, %u drawn", what, pages.maps, maps, pages.requested,
                    pages.cached, pages.drawn);
        ImGui::Text("  %u allocated, %u evicted, %u overflowed, %u deferred", pages.allocated, pages.evicted, pages.overflowed,
                    pages.deferred);
        char label[64];
        std::snprintf(label, sizeof label, "pool %u / %u pages", pages.resident, pages.poolPages);
        ImGui::ProgressBar(pages.poolPages > 0 ? float(pages.resident) / float(pages.poolPages) : 0.0f,
                           ImVec2(-1.0f, 0.0f), label);
    };
    if (const VirtualPageCounts& pages = last.virtualPages; pages.maps > 0) {
        counts("virtual pages", "maps", pages);
        if (ImGui::CollapsingHeader("virtual pages per level"))
            for (uint32_t map = 0; map < std::min<uint32_t>(pages.maps, uint32_t(last.virtualMaps.size())); ++map) {
                char id[32];
                std::snprintf(id, sizeof id, "levels%u", map);
                ImGui::Text("directional light %u", map);
                drawLevelTable(id, "level", last.virtualMaps[map]);
            }
    }
    if (const VirtualPageCounts& faces = last.virtualFacePages; faces.maps > 0) {
        counts("spot/point virtual pages", "faces", faces);
        if (ImGui::CollapsingHeader("spot/point virtual pages per mip")) drawLevelTable("faceMips", "mip", last.virtualFaceMips);
    }
}

void drawStatsPanel(PanelContext& c) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 348, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 420), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Stats") || c.state.history.empty()) {
        ImGui::End();
        return;
    }
    const FrameStats& last = c.state.history.back();
    std::vector<float> gpu;
    for (const FrameStats& stats : c.state.history) gpu.push_back(float(totalGpuMs(stats)));
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "GPU %.2f ms", gpu.back());
    // PlotLines (ImGui 1.86) takes its width as given: -1 would be a graph one pixel wide.
    ImGui::PlotLines("##gpu", gpu.data(), int(gpu.size()), 0, overlay, 0.0f, *std::max_element(gpu.begin(), gpu.end()) * 1.2f,
                     ImVec2(ImGui::GetContentRegionAvail().x, 60));
    if (ImGui::BeginTable("passes", 2)) {
        for (const PassTiming& timing : last.gpuTimings) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(timing.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f ms", timing.milliseconds);
        }
        ImGui::EndTable();
    }
    ImGui::Text("CPU ms: plan %.2f  culling %.2f  upload %.2f", last.cpu.plan, last.cpu.culling, last.cpu.upload);
    ImGui::Text("        record %.2f  submit %.2f  readback %.2f", last.cpu.record, last.cpu.submit, last.cpu.readback);
    ImGui::Text("frame (submit to fence) %.2f ms", last.submitToFenceMilliseconds);
    ImGui::Text("shadow raster %s; tiles drawn %u, reused %u", last.shadowRaster.c_str(), last.tilesRendered, last.tilesReused);
    drawVirtualPageView(last);
    for (const AtlasDrawStats& atlas : last.atlases)
        ImGui::Text("%s: %u tiles, %u draws, %llu triangles", atlas.pass.c_str(), atlas.tiles, atlas.draws,
                    static_cast<unsigned long long>(atlas.triangles));
    ImGui::TextWrapped("%s", shadowLightCounts(last.shadows).c_str());
    const auto atlasLines = [](const char* atlas, const auto& a, auto drawnOf) {
        ImGui::Text("%s %u^2: %u tiles of %u^2, %.0f %% used", atlas, a.atlasSize, a.tiles, a.tileSize, 100.0 * a.occupancy);
        std::vector<uint64_t> casters, triangles;
        for (const auto& tile : a.tileStats) {
            casters.push_back(drawnOf(tile).casters);
            triangles.push_back(drawnOf(tile).triangles);
        }
        ImGui::TextWrapped("  casters per tile: %s", countList(casters).c_str());
        if (a.trianglesCounted) ImGui::TextWrapped("  triangles per tile: %s", countList(triangles).c_str());
    };
    atlasLines("directional", last.shadows.directional, [](const DirectionalTileStats& t) { return t.drawn; });
    atlasLines("other", last.shadows.other, [](const ShadowTileDraws& t) { return t; });
    for (const std::string& warning : last.warnings) ImGui::TextWrapped("warning: %s", warning.c_str());
    ImGui::End();
}

void drawSplitLabels(const std::string& compareSettingsPath) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->AddLine(ImVec2(display.x * 0.5f, 0.0f), ImVec2(display.x * 0.5f, display.y), IM_COL32(255, 255, 255, 160));
    const float y = display.y - ImGui::GetTextLineHeight() - 30.0f;
    draw->AddText(ImVec2(display.x * 0.5f - 130.0f, y), IM_COL32(255, 255, 255, 255), "current settings");
    draw->AddText(ImVec2(display.x * 0.5f + 8.0f, y), IM_COL32(255, 255, 255, 255), compareSettingsPath.c_str());
}

bool drawReferencePanel(ReferenceComparison& comparison, bool showPanels) {
    const ReferenceComparison::State state = comparison.state();
    if (state == ReferenceComparison::State::Ready && !showPanels) return false;  // the picture alone
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y - 8.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(std::min(display.x - 16.0f, 360.0f), 0.0f), ImGuiCond_Always);
    bool pressed = false;
    if (ImGui::Begin("Reference", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoResize)) {
        if (state == ReferenceComparison::State::Tracing) {
            ImGui::ProgressBar(comparison.progress(), ImVec2(-1.0f, 0.0f), "tracing the reference");
        } else if (state == ReferenceComparison::State::Ready) {
            const CompareMetrics& m = comparison.metrics();
            ImGui::Text("misclassified %.3f %% of %llu valid pixels", m.misclassifiedPercent,
                        static_cast<unsigned long long>(m.validPixels));
            ImGui::Text("false shadow (red) %.3f %%, false lit (cyan) %.3f %%", m.falseShadowPercent, m.falseLitPercent);
            pressed = ImGui::Button("Trace again (T)");
        } else {
            if (state == ReferenceComparison::State::Failed) ImGui::TextWrapped("%s", comparison.error().c_str());
            pressed = ImGui::Button("Compare with the ray-traced reference (T)");
        }
    }
    ImGui::End();
    return pressed;
}

void drawAtlasLabels(const std::vector<AtlasTileLabel>& labels, const glm::vec4& windowRect, const glm::vec2& atlasSize) {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const glm::vec2 origin(windowRect.x, windowRect.y);
    const glm::vec2 scale = glm::vec2(windowRect.z - windowRect.x, windowRect.w - windowRect.y) / atlasSize;
    draw->AddRect(ImVec2(windowRect.x, windowRect.y), ImVec2(windowRect.z, windowRect.w), IM_COL32(255, 200, 0, 255));
    for (const AtlasTileLabel& label : labels) {
        const glm::vec2 min = origin + label.min * scale, max = origin + label.max * scale;
        draw->AddRect(ImVec2(min.x, min.y), ImVec2(max.x, max.y), IM_COL32(255, 200, 0, 255));
        draw->AddText(ImVec2(min.x + 3, min.y + 2), IM_COL32(255, 200, 0, 255), label.text.c_str());
    }
}

}  // namespace penumbra::viewer
