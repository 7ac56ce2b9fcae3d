// The settings inspector: one widget per key of the settings table (penumbra/settings_keys.h), with
// the table's range (each slider and drag clamps to it, a typed Ctrl+click value too); a change
// applies to the next frame, one validation refuses is the status line.
#include <algorithm>
#include <cfloat>
#include <string>

#include <imgui.h>

#include "viewer/panel_data.h"
#include "viewer/panels.h"
#include "viewer/settings_edit.h"
#include "viewer/viewer_app.h"

namespace penumbra::viewer {

namespace {

// The cascades as a bar split like the cascade bar of Unity URP's pipeline asset: one coloured span per
// cascade, where it ends as a share of shadows.maxDistance: the ratios with manual splits, else the last
// frame's computed splits (marked so: the ratios below apply to manual splits only).
void drawSplitBar(const Settings& settings, const ShadowPlanStats& shadows) {
    const SplitBar bar = splitBarOf(settings, shadows);
    if (bar.computed)
        ImGui::TextDisabled("computed %s splits of the last frame (ratios: manual only)",
                            cascadeSplitModeName(settings.shadows.directional.cascadeSplits));
    const ImU32 colours[] = {IM_COL32(90, 140, 230, 255), IM_COL32(90, 200, 110, 255), IM_COL32(230, 200, 80, 255),
                             IM_COL32(220, 90, 90, 255)};
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x, height = 16.0f;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(60, 60, 60, 255));  // beyond the last
    float start = 0.0f;
    for (size_t c = 0; c < bar.ends.size(); ++c) {
        draw->AddRectFilled(ImVec2(origin.x + start * width, origin.y), ImVec2(origin.x + bar.ends[c] * width, origin.y + height),
                            colours[c % 4]);
        start = bar.ends[c];
    }
    ImGui::Dummy(ImVec2(width, height));
}

// One widget for element `i` of `key`; returns the value the user chose, or the current one.
double keyWidget(const SettingKey& key, size_t i, double value, const std::string& label) {
    const std::vector<double> offered = inspectorValues(key);
    switch (key.type) {
        case SettingType::Bool: {
            bool on = value != 0.0;
            ImGui::Checkbox(label.c_str(), &on);
            return on ? 1.0 : 0.0;
        }
        case SettingType::Choice:
        case SettingType::PowerOfTwo: {
            const auto current = std::find(offered.begin(), offered.end(), value);
            const std::string preview = key.type == SettingType::Choice ? key.choices.at(size_t(value)) : std::to_string(int(value));
            if (ImGui::BeginCombo(label.c_str(), preview.c_str())) {
                for (double v : offered) {
                    const std::string name = key.type == SettingType::Choice ? key.choices.at(size_t(v)) : std::to_string(int(v));
                    if (ImGui::Selectable(name.c_str(), current != offered.end() && *current == v)) value = v;
                }
                ImGui::EndCombo();
            }
            return value;
        }
        case SettingType::Integer: {
            int n = int(value);
            ImGui::SliderInt(label.c_str(), &n, int(key.min), int(key.max), "%d", ImGuiSliderFlags_AlwaysClamp);
            return double(n);
        }
        case SettingType::Number:
        case SettingType::Ratios: {
            float f = float(value);
            if (key.max <= 1000.0)
                ImGui::SliderFloat(label.c_str(), &f, float(offered[0]), float(offered[1]), "%.3f", ImGuiSliderFlags_AlwaysClamp);
            else
                ImGui::DragFloat(label.c_str(), &f, 0.1f, float(offered[0]), FLT_MAX, "%.3f", ImGuiSliderFlags_AlwaysClamp);
            (void)i;
            return double(f);
        }
    }
    return value;
}

}  // namespace

void drawSettingsInspector(PanelContext& c) {
    for (const SettingKey& key : settingKeys()) {
        ImGui::PushID(key.key);
        const std::string label = std::string(key.key).substr(std::string(key.key).find('.') + 1);
        if (key.type == SettingType::Ratios)
            drawSplitBar(c.settings, c.state.history.empty() ? ShadowPlanStats{} : c.state.history.back().shadows);
        for (size_t i = 0; i < key.elements(); ++i) {
            ImGui::PushID(int(i));
            const double value = key.get(c.settings, i);
            const std::string elementLabel = key.type == SettingType::Ratios ? label + "[" + std::to_string(i) + "]" : label;
            const double chosen = keyWidget(key, i, value, elementLabel);
            if (ImGui::IsItemHovered()) {  // the key, its range and what it does (docs/settings.md's text)
                ImGui::BeginTooltip();
                ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
                ImGui::Text("%s: %s", key.key, key.allowed.c_str());
                ImGui::TextUnformatted(key.description.c_str());
                ImGui::PopTextWrapPos();
                ImGui::EndTooltip();
            }
            if (chosen != value) {
                const std::string error = applyInspectorEdit(c.settings, key, i, chosen);
                if (!error.empty()) c.state.status = error;
            }
            ImGui::PopID();
        }
        ImGui::PopID();
    }
    ImGui::InputText("##save", c.state.settingsSavePath, sizeof c.state.settingsSavePath);
    ImGui::SameLine();
    if (ImGui::Button("Save settings")) {
        const std::string path = c.state.settingsSavePath;
        const std::string error = saveSettingsFile(c.settings, path);
        c.state.status = error.empty() ? "saved " + path : error;
    }
}

}  // namespace penumbra::viewer
