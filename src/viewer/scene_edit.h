#pragma once
// What the scene inspector does with a value, without a window (so it is unit-tested): the range of
// each light widget, and one edit applied through a Renderer setter, whose validation may refuse it.
// A refused edit leaves the scene as it was and becomes the panel's status line; the viewer goes on.
#include <functional>
#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::viewer {

// One number of a light the inspector edits: its label, its field, the widget's range (the widget
// clamps to it, typed values included) and its drag speed (0: a slider).
struct LightWidget {
    const char* label;
    float Light::*field;
    float min, max, speed;
};

// The light's number widgets (strength, biases, near plane, emitter size in degrees for a sun, in
// metres otherwise): every value in their ranges is one the scene's validation accepts.
std::vector<LightWidget> lightWidgets(LightType type);
// The position widget's range per axis (metres).
inline constexpr float kLightPositionLimit = 1.0e9f;

// Runs one edit (e.g. renderer.setLight(i, light)); "" when it was applied, else the message of the
// penumbra::Error that refused it (the setter changed nothing).
std::string applySceneEdit(const std::function<void()>& edit);

}  // namespace penumbra::viewer
