// The scene inspector: per light its shadows (none / hard / soft / pcss), strength, biases, near
// plane, emitter size, direction and position; per material its shadow mode and receive shadows; per
// node cast shadows. Every change goes through the Renderer's scene-edit API and shows next frame.
#include <cmath>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <imgui.h>

#include "viewer/panels.h"

namespace penumbra::viewer {

namespace {

const char* lightTypeName(LightType type) {
    return type == LightType::Directional ? "sun" : type == LightType::Spot ? "spot" : "point";
}

bool editDirection(glm::vec3& wsDirection) {
    // Azimuth and elevation of the direction the light travels, in degrees.
    float azimuth = glm::degrees(std::atan2(wsDirection.x, -wsDirection.z));
    float elevation = glm::degrees(std::asin(glm::clamp(-wsDirection.y, -1.0f, 1.0f)));
    bool changed = ImGui::SliderFloat("azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
    changed |= ImGui::SliderFloat("elevation", &elevation, -89.9f, 89.9f, "%.1f deg");
    if (changed) {
        const float a = glm::radians(azimuth), e = glm::radians(elevation);
        wsDirection = glm::vec3(std::sin(a) * std::cos(e), -std::sin(e), -std::cos(a) * std::cos(e));
    }
    return changed;
}

void editLight(Renderer& renderer, uint32_t index) {
    Light light = renderer.scene().lights[index];
    bool changed = false;
    int shadows = int(light.shadows);
    const char* modes[] = {"none", "hard", "soft", "pcss"};
    changed |= ImGui::Combo("shadows", &shadows, modes, 4);
    light.shadows = LightShadows(shadows);
    changed |= ImGui::SliderFloat("strength", &light.shadowStrength, 0.0f, 1.0f);
    changed |= ImGui::DragFloat("slope bias", &light.shadowBias, 0.01f, 0.0f, 10.0f);
    changed |= ImGui::DragFloat("normal bias", &light.shadowNormalBias, 0.01f, 0.0f, 10.0f);
    changed |= ImGui::DragFloat("near plane", &light.shadowNearPlane, 0.01f, 0.0f, 100.0f);
    const bool sun = light.type == LightType::Directional;
    changed |= ImGui::DragFloat(sun ? "light size (deg)" : "light radius (m)", &light.shadowLightSize, 0.01f, 0.0f,
                                sun ? 20.0f : 10.0f);
    changed |= editDirection(light.wsDirection);
    if (!sun) changed |= ImGui::DragFloat3("position", glm::value_ptr(light.wsPosition), 0.05f);
    if (changed) renderer.setLight(index, light);
}

}  // namespace

void drawSceneInspector(PanelContext& c) {
    Renderer& renderer = c.renderer;
    const Scene& scene = renderer.scene();
    if (ImGui::TreeNode("Lights")) {
        for (uint32_t i = 0; i < scene.lights.size(); ++i) {
            ImGui::PushID(int(i));
            if (ImGui::TreeNode("light", "%u: %s", i, lightTypeName(scene.lights[i].type))) {
                editLight(renderer, i);
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
            if (changed) renderer.setMaterial(i, material);
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
                renderer.setInstanceCastShadows(i, cast);
            ImGui::PopID();
        }
        ImGui::TreePop();
    }
}

}  // namespace penumbra::viewer
