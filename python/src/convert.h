#pragma once
// Conversions between Python objects and the public API's types, for the penumbra module. Every
// check of a caller's value throws penumbra::Error with one line (the module turns it into
// penumbra.Error), so that no bad argument reaches the library as undefined behaviour.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <penumbra/camera.h>
#include <penumbra/image.h>
#include <penumbra/scene.h>
#include <penumbra/settings.h>

namespace penumbra::python {

namespace py = pybind11;

// ---- settings: a dict of dotted keys ("shadows.directional.filter") or nested dicts, values as in
// the settings JSON (numbers, strings, booleans, a list of 3 for the ratios). Each key is applied as
// the CLI's --set key=value, so a bad one gives the CLI's message. None = the defaults.
Settings settingsFromPython(const py::handle& settings);
// Every key's value, flat: {"shadows.directional.filter": "PCF3x3", ...}.
py::dict settingsToPython(const Settings& settings);

// ---- JSON text (from the library's toJson functions) as Python objects, through Python's json.
py::object jsonToPython(const std::string& jsonText);

// ---- numbers and vectors
// An integer argument in [low, high], or Error "<what> must be an integer from low to high (got ...)".
uint32_t checkedIndex(const py::handle& value, const char* what, int64_t low, int64_t high);
// A finite number (not a bool), or Error "<what> = <value> has the wrong type (expected a number)".
float floatFromPython(const py::handle& value, const std::string& what);
// True or False (or numpy.bool_).
bool boolFromPython(const py::handle& value, const std::string& what);
// `count` finite numbers from any sequence of them.
std::vector<float> numbersFromPython(const py::handle& value, const std::string& what, size_t count);
// A finite 3-vector from any sequence of 3 numbers.
glm::vec3 vec3FromPython(const py::handle& value, const std::string& what);
// A 4x4 matrix from a (4, 4) array of numbers, rows first (numpy's convention: M @ [x, y, z, 1]).
glm::mat4 mat4FromPython(const py::handle& value, const std::string& what);
py::array_t<double> mat4ToPython(const glm::mat4& m);

// ---- arrays: exact dtype kinds and shapes, or Error naming what was expected.
// A C-contiguous float32 copy of a floating-point array of shape (N, columns).
py::array_t<float> floatRows(const py::handle& value, const std::string& what, size_t columns);
// A uint32 copy of an integer array of shape (N, 3) or (3N,), every value checked >= 0 and < limit.
std::vector<uint32_t> triangleIndices(const py::handle& value, const std::string& what, size_t limit);

// ---- images as arrays: uint8 (H, W, 4) RGBA for colour (alpha 255), float32 (H, W) in [0, 1] for
// the shadow AOV (value / 255), uint8 (H, W, 3) for the cascades AOV.
py::array imageToPython(const Image& image, bool rgba);
py::array_t<float> shadowToPython(const Image& image);
// A shadow image from an (H, W) array: float32/float64 in [0, 1] (rounded to 8 bits as the AOV
// stores it; NaN allowed only with `nanAllowed`, then stored 255 and reported in `nanMask`) or uint8.
Image shadowFromPython(const py::handle& value, const std::string& what, bool nanAllowed, Image* nanMask);

// ---- camera: {"position": (x, y, z), "target": (x, y, z), "fov": degrees, "near": m, "far": m}, world
// space, vertical field of view; or None (nullopt) for the scene's camera.
std::optional<Camera> cameraFromPython(const py::handle& camera);
// The view of `camera`, or of the scene's own camera, for an output of width x height.
CameraView cameraView(const std::optional<Camera>& camera, const Scene& scene, uint32_t width, uint32_t height);

// ---- lights as dicts (name, type, shadows and the fields of kLightFields), and partial updates of one.
py::dict lightToPython(const Light& light);
Light lightFromPython(const py::handle& values, Light light, const std::string& what);

}  // namespace penumbra::python
