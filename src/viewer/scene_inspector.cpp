// The scene inspector: per light its shadows (none / hard / soft / pcss), strength, biases, near
// plane, emitter size, direction and position; per material its shadow mode and receive shadows; per
// node cast shadows. Every change goes through the Renderer's scene-edit API and shows next frame; a
// value the API refuses is the status line (scene_edit.h). Every slider and drag clamps to its range,
// a typed (Ctrl+click) value too.
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <imgui.h>

#include "viewer/panels.h"
#include "viewer/scene_edit.h"
#include "viewer/viewer_app.h"

namespace penumbra::viewer {

namespace {

constexpr ImGuiSliderFlags kClamp = ImGuiSliderFlags_AlwaysClamp;

// One edit through the Renderer; a refused one is the status line and one line on stderr.
void edit(PanelContext& c, const std::function<void()>& change) {
    const std::string error = applySceneEdit(change);
    if (error.empty()) return;
    c.state.status = error;
    std::fprintf(stderr, "penumbra-viewer: %s\n", error.c_str());
}

const char* lightTypeName(LightType type) {
    return type == LightType::Directional ? "sun" : type == LightType::Spot ? "spot" : "point";
}

bool editDirection(glm::vec3& wsDirection) {
    // Azimuth and elevation of the direction the light travels, in degrees.
    float azimuth = glm::degrees(std::atan2(wsDirection.x, -wsDirection.z));
    float elevation = glm::degrees(std::asin(glm::clamp(-wsDirection.y, -1.0f, 1.0f)));
    bool changed = ImGui::SliderFloat("azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg", kClamp);
    changed |= ImGui::SliderFloat("elevation", &elevation, -89.9f, 89.9f, "%.1f deg", kClamp);
    if (changed) {
        const float a = glm::radians(azimuth), e = glm::radians(elevation);
        wsDirection = glm::vec3(std::sin(a) * std::cos(e), -std::sin(e), -std::cos(a) * std::cos(e));
    }
    return changed;
}

void editLight(PanelContext& c, uint32_t index) {
    Light light = c.renderer.scene().lights[index];
    bool changed = false;
    int shadows = int(light.shadows);
    const char* modes[] = {"none", "hard", "soft", "pcss"};
    changed |= ImGui::Combo("shadows", &shadows, modes, 4);
    light.shadows = LightShadows(shadows);
    for (const LightWidget& w : lightWidgets(light.type))
        changed |= w.speed > 0.0f ? ImGui::DragFloat(w.label, &(light.*w.field), w.speed, w.min, w.max, "%.3f", kClamp)
                                  : ImGui::SliderFloat(w.label, &(light.*w.field), w.min, w.max, "%.3f", kClamp);
    changed |= editDirection(light.wsDirection);
    if (light.type != LightType::Directional)
        changed |= ImGui::DragFloat3("position", glm::value_ptr(light.wsPosition), 0.05f, -kLightPositionLimit,
                                     kLightPositionLimit, "%.3f", kClamp);
    if (changed) edit(c, [&] { c.renderer.setLight(index, light); });
}

}  // namespace

void drawSceneInspector(PanelContext& c) {
    Renderer& renderer = c.renderer;
    const Scene& scene = renderer.scene();
    if (ImGui::TreeNode("Lights")) {
        for (uint32_t i = 0; i < scene.lights.size(); ++i) {
            ImGui::PushID(int(i));
            if (ImGui::TreeNode("light", "%u: %s", i, lightTypeName(scene.lights[i].type))) {
                editLight(c, i);
                ImGui::TreePop();
            }
            ImGui::PopID();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNode("Materials")) {
        for (uint32_t i = 0; i < scene.materials.size(); ++i) {
            ImGui::PushID(int(i));
            Material material = scene.materials[i];
            ImGui::Text("%u: %s", i, material.name.empty() ? "(unnamed)" : material.name.c_str());
            int mode = int(material.shadows);
            const char* modes[] = {"on", "clip", "dither", "off"};
            bool changed = ImGui::Combo("shadow mode", &mode, modes, 4);
            material.shadows = MaterialShadowMode(mode);
            changed |= ImGui::Checkbox("receive shadows", &material.receiveShadows);
            if (changed) edit(c, [&] { renderer.setMaterial(i, material); });
            ImGui::PopID();
        }
        ImGui::TreePop();
    }
    if (ImGui::TreeNode("Nodes")) {
        for (uint32_t i = 0; i < scene.instances.size(); ++i) {
            ImGui::PushID(int(i));
            bool cast = scene.instances[i].castShadows;
            const std::string& name = scene.instances[i].nodeName;
            if (ImGui::Checkbox(name.empty() ? ("instance " + std::to_string(i)).c_str() : name.c_str(), &cast))
                edit(c, [&] { renderer.setInstanceCastShadows(i, cast); });
            ImGui::PopID();
        }
        ImGui::TreePop();
    }
}

}  // namespace penumbra::viewer
