#include "convert.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <penumbra/error.h>
#include <penumbra/scene_builder.h>
#include <penumbra/settings_keys.h>

namespace penumbra::python {

namespace {

std::string typeName(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

std::string shortRepr(const py::handle& value) {
    std::string text = py::repr(value);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

// "float64 of shape (4, 3)" or "list" for the messages about arrays.
std::string describeArray(const py::array& array) {
    std::string shape;
    for (py::ssize_t i = 0; i < array.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(array.shape(i));
    if (array.ndim() == 1) shape += ",";
    return std::string(py::str(array.dtype())) + " of shape (" + shape + ")";
}

py::array asArray(const py::handle& value) { return py::module_::import("numpy").attr("asarray")(value); }

// 'f' floating, 'i' signed, 'u' unsigned, 'b' bool, ...
char dtypeKind(const py::array& array) { return py::str(array.dtype().attr("kind")).cast<std::string>()[0]; }

// The settings JSON text of one value: the CLI's --set value for it.
std::string settingValueJson(const std::string& key, const py::handle& value) {
    py::object plain = py::reinterpret_borrow<py::object>(value);
    const py::module_ numpy = py::module_::import("numpy");
    if (py::isinstance(plain, numpy.attr("ndarray"))) plain = plain.attr("tolist")();
    else if (py::isinstance(plain, numpy.attr("generic"))) plain = plain.attr("item")();
    try {
        return py::module_::import("json").attr("dumps")(plain, py::arg("allow_nan") = false).cast<std::string>();
    } catch (const py::error_already_set& error) {
        if (!error.matches(PyExc_TypeError) && !error.matches(PyExc_ValueError)) throw;
        throw Error("settings: " + key + " = " + shortRepr(value) +
                    " has the wrong type (expected a finite number, a string, true or false, or a list of numbers)");
    }
}

void flattenSettings(const py::dict& settings, const std::string& prefix,
                     std::vector<std::pair<std::string, py::handle>>& leaves) {
    for (const auto& [key, value] : settings) {
        if (!py::isinstance<py::str>(key))
            throw Error("settings: the keys must be strings (got " + shortRepr(key) + ")");
        const std::string name = prefix + key.cast<std::string>();
        if (py::isinstance<py::dict>(value))
            flattenSettings(py::reinterpret_borrow<py::dict>(value), name + ".", leaves);
        else
            leaves.emplace_back(name, value);
    }
}

void flattenJson(const py::handle& node, const std::string& prefix, py::dict& out) {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(node)) {
        const std::string name = prefix + key.cast<std::string>();
        if (py::isinstance<py::dict>(value))
            flattenJson(value, name + ".", out);
        else
            out[py::str(name)] = value;
    }
}

const char* const kLightTypes[] = {"directional", "spot", "point"};
const char* const kLightShadows[] = {"none", "hard", "soft", "pcss"};

template <size_t N>
int choiceIndex(const py::handle& value, const char* const (&names)[N], const std::string& what) {
    if (py::isinstance<py::str>(value)) {
        const std::string name = value.cast<std::string>();
        for (size_t i = 0; i < N; ++i)
            if (name == names[i]) return int(i);
    }
    std::string allowed;
    for (size_t i = 0; i < N; ++i) allowed += (i ? ", " : "") + std::string(names[i]);
    throw Error(what + " = " + shortRepr(value) + " is out of range (allowed " + allowed + ")");
}

}  // namespace

float floatFromPython(const py::handle& value, const std::string& what) {
    if (py::isinstance<py::bool_>(value) || !PyNumber_Check(value.ptr()) || py::isinstance<py::str>(value))
        throw Error(what + " = " + shortRepr(value) + " has the wrong type (expected a number)");
    double number = 0.0;
    try {
        number = py::float_(py::reinterpret_borrow<py::object>(value));
    } catch (const py::error_already_set&) {
        throw Error(what + " = " + shortRepr(value) + " has the wrong type (expected a number)");
    }
    if (!std::isfinite(number)) throw Error(what + " = " + shortRepr(value) + " is not finite");
    return float(number);
}

bool boolFromPython(const py::handle& value, const std::string& what) {
    if (!py::isinstance<py::bool_>(value) && !py::isinstance(value, py::module_::import("numpy").attr("bool_")))
        throw Error(what + " = " + shortRepr(value) + " has the wrong type (expected True or False)");
    return py::bool_(py::reinterpret_borrow<py::object>(value));
}

Settings settingsFromPython(const py::handle& settings) {
    Settings result;
    if (settings.is_none()) return result;
    if (!py::isinstance<py::dict>(settings))
        throw Error("settings: expected a dict of setting keys and values (got " + typeName(settings) + ")");
    std::vector<std::pair<std::string, py::handle>> leaves;
    flattenSettings(py::reinterpret_borrow<py::dict>(settings), "", leaves);
    for (const auto& [key, value] : leaves) applySettingOverride(result, key + "=" + settingValueJson(key, value));
    validateSettings(result);
    return result;
}

py::dict settingsToPython(const Settings& settings) {
    py::dict flat;
    flattenJson(jsonToPython(settingsToJson(settings)), "", flat);
    return flat;
}

py::object jsonToPython(const std::string& jsonText) { return py::module_::import("json").attr("loads")(jsonText); }

uint32_t checkedIndex(const py::handle& value, const char* what, int64_t low, int64_t high) {
    PyObject* index = py::isinstance<py::bool_>(value) ? nullptr : PyNumber_Index(value.ptr());
    if (!index) {
        PyErr_Clear();
        throw Error(std::string(what) + " must be an integer (got " + shortRepr(value) + ")");
    }
    const py::object number = py::reinterpret_steal<py::object>(index);
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
    if (overflow != 0 || v < low || v > high)
        throw Error(std::string(what) + " must be an integer from " + std::to_string(low) + " to " + std::to_string(high) +
                    " (got " + shortRepr(value) + ")");
    return uint32_t(v);
}

std::vector<float> numbersFromPython(const py::handle& value, const std::string& what, size_t count) {
    const std::string expected = what + " must be " + std::to_string(count) + " numbers (got " + shortRepr(value) + ")";
    py::array array;
    try {
        array = py::module_::import("numpy").attr("asarray")(value, py::arg("dtype") = "float64");
    } catch (const py::error_already_set&) {
        throw Error(expected);
    }
    if (array.ndim() != 1 || size_t(array.shape(0)) != count) throw Error(expected);
    const py::array_t<double, py::array::c_style> doubles(array);
    std::vector<float> numbers(count);
    for (size_t i = 0; i < count; ++i) {
        numbers[i] = float(doubles.data()[i]);
        if (!std::isfinite(numbers[i])) throw Error(what + " must be finite (got " + shortRepr(value) + ")");
    }
    return numbers;
}

glm::vec3 vec3FromPython(const py::handle& value, const std::string& what) {
    const std::vector<float> v = numbersFromPython(value, what, 3);
    return glm::vec3(v[0], v[1], v[2]);
}

glm::mat4 mat4FromPython(const py::handle& value, const std::string& what) {
    const py::array array = asArray(value);
    if (array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4 || !(dtypeKind(array) == 'f' || dtypeKind(array) == 'i' || dtypeKind(array) == 'u'))
        throw Error(what + " must be a (4, 4) array of numbers (got " + describeArray(array) + ")");
    const py::array_t<double, py::array::c_style | py::array::forcecast> rows(array);
    glm::mat4 m;
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            const double v = rows.at(row, column);
            if (!std::isfinite(v)) throw Error(what + " must be finite");
            m[column][row] = float(v);  // glm is column-major
        }
    return m;
}

py::array_t<double> mat4ToPython(const glm::mat4& m) {
    py::array_t<double> rows({4, 4});
    auto out = rows.mutable_unchecked<2>();
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) out(row, column) = m[column][row];
    return rows;
}

py::array_t<float> floatRows(const py::handle& value, const std::string& what, size_t columns) {
    const py::array array = asArray(value);
    if (dtypeKind(array) != 'f' || array.ndim() != 2 || size_t(array.shape(1)) != columns)
        throw Error(what + " must be a floating-point array of shape (N, " + std::to_string(columns) + ") (got " +
                    describeArray(array) + ")");
    return py::array_t<float, py::array::c_style | py::array::forcecast>(array);
}

std::vector<uint32_t> triangleIndices(const py::handle& value, const std::string& what, size_t limit) {
    const py::array array = asArray(value);
    const char kind = dtypeKind(array);
    const bool shaped = (array.ndim() == 2 && array.shape(1) == 3) || (array.ndim() == 1 && array.shape(0) % 3 == 0);
    if ((kind != 'i' && kind != 'u') || !shaped)
        throw Error(what + " must be an integer array of shape (N, 3) or (3N,) (got " + describeArray(array) + ")");
    const py::array_t<int64_t, py::array::c_style | py::array::forcecast> values(array);
    std::vector<uint32_t> indices(size_t(values.size()));
    const int64_t* data = values.data();
    for (size_t i = 0; i < indices.size(); ++i) {
        if (data[i] < 0 || uint64_t(data[i]) >= limit)
            throw Error(what + ": index " + std::to_string(i) + " is " + std::to_string(data[i]) +
                        ", not from 0 to the vertex count " + std::to_string(limit) + " - 1");
        indices[i] = uint32_t(data[i]);
    }
    return indices;
}

py::array imageToPython(const Image& image, bool rgba) {
    const size_t pixels = size_t(image.width) * image.height;
    const uint32_t channels = rgba ? 4 : image.channels;
    py::array_t<uint8_t> array({size_t(image.height), size_t(image.width), size_t(channels)});
    uint8_t* out = array.mutable_data();
    for (size_t p = 0; p < pixels; ++p)
        for (uint32_t c = 0; c < channels; ++c)
            out[p * channels + c] = c < image.channels ? image.pixels[p * image.channels + c] : uint8_t(255);
    return array;
}

py::array_t<float> shadowToPython(const Image& image) {
    py::array_t<float> array({size_t(image.height), size_t(image.width)});
    float* out = array.mutable_data();
    for (size_t p = 0; p < image.pixels.size(); ++p) out[p] = float(image.pixels[p * image.channels]) / 255.0f;
    return array;
}

Image shadowFromPython(const py::handle& value, const std::string& what, bool nanAllowed, Image* nanMask) {
    const py::array array = asArray(value);
    const char kind = dtypeKind(array);
    const bool uint8 = kind == 'u' && array.itemsize() == 1;
    if (array.ndim() != 2 || (kind != 'f' && !uint8) || array.shape(0) == 0 || array.shape(1) == 0)
        throw Error(what + " must be a float32 or uint8 array of shape (H, W) (got " + describeArray(array) + ")");
    Image image(uint32_t(array.shape(1)), uint32_t(array.shape(0)), 1);
    if (nanMask) *nanMask = Image(image.width, image.height, 1, 0);
    if (uint8) {
        const py::array_t<uint8_t, py::array::c_style | py::array::forcecast> bytes(array);
        std::copy_n(bytes.data(), image.pixels.size(), image.pixels.begin());
        return image;
    }
    const py::array_t<float, py::array::c_style | py::array::forcecast> values(array);
    for (size_t p = 0; p < image.pixels.size(); ++p) {
        const float v = values.data()[p];
        if (std::isnan(v) && nanAllowed) {
            image.pixels[p] = 255;
            if (nanMask) nanMask->pixels[p] = 255;
            continue;
        }
        if (!(v >= 0.0f && v <= 1.0f))
            throw Error(what + " must hold values from 0 to 1" + (nanAllowed ? " or NaN" : "") + " (pixel (" +
                        std::to_string(p % image.width) + ", " + std::to_string(p / image.width) + ") is " +
                        std::to_string(v) + ")");
        image.pixels[p] = uint8_t(std::lround(v * 255.0f));
    }
    return image;
}

std::optional<Camera> cameraFromPython(const py::handle& camera) {
    if (camera.is_none()) return std::nullopt;
    if (!py::isinstance<py::dict>(camera))
        throw Error("camera must be a dict with position, target and fov, or None (got " + typeName(camera) + ")");
    const py::dict values = py::reinterpret_borrow<py::dict>(camera);
    for (const auto& [key, value] : values) {
        const std::string name = py::str(key);
        if (name != "position" && name != "target" && name != "fov" && name != "near" && name != "far")
            throw Error("camera: unknown key '" + name + "' (allowed position, target, fov, near, far)");
    }
    if (!values.contains("position") || !values.contains("target"))
        throw Error("camera: position and target are required");
    const glm::vec3 wsPosition = vec3FromPython(values["position"], "camera position");
    const glm::vec3 wsTarget = vec3FromPython(values["target"], "camera target");
    const float fovDegrees = values.contains("fov") ? floatFromPython(values["fov"], "camera fov") : 45.0f;
    const float zNear = values.contains("near") ? floatFromPython(values["near"], "camera near") : 0.1f;
    float zFar = std::numeric_limits<float>::infinity();
    if (values.contains("far") && !values["far"].is_none()) {
        const py::object far = values["far"];
        const bool infinite = PyFloat_Check(far.ptr()) && std::isinf(PyFloat_AsDouble(far.ptr())) && PyFloat_AsDouble(far.ptr()) > 0;
        if (!infinite) zFar = floatFromPython(far, "camera far");
    }
    if (!(glm::length(wsTarget - wsPosition) > 1e-6f)) throw Error("camera: position and target must differ");
    if (!(fovDegrees > 0.0f && fovDegrees < 180.0f))
        throw Error("camera fov = " + std::to_string(fovDegrees) + " is out of range (allowed degrees in (0, 180))");
    if (!(zNear > 0.0f && zFar > zNear)) throw Error("camera: near must be > 0 and far > near");
    return makeLookAtCamera(wsPosition, wsTarget, glm::radians(fovDegrees), zNear, zFar);
}

CameraView cameraView(const std::optional<Camera>& camera, const Scene& scene, uint32_t width, uint32_t height) {
    return camera ? makeCameraView(*camera, width, height) : resolveCameraView(scene, width, height);
}

namespace {

// The light's number and vector fields under their Python keys; name, type and shadows are strings.
struct LightField {
    const char* key;
    float Light::*number;
    glm::vec3 Light::*vector;
};
constexpr LightField kLightFields[] = {
    {"color", nullptr, &Light::color},
    {"intensity", &Light::intensity, nullptr},
    {"range", &Light::range, nullptr},
    {"inner_cone_angle", &Light::innerConeAngle, nullptr},
    {"outer_cone_angle", &Light::outerConeAngle, nullptr},
    {"ws_position", nullptr, &Light::wsPosition},
    {"ws_direction", nullptr, &Light::wsDirection},
    {"shadow_strength", &Light::shadowStrength, nullptr},
    {"shadow_bias", &Light::shadowBias, nullptr},
    {"shadow_normal_bias", &Light::shadowNormalBias, nullptr},
    {"shadow_near_plane", &Light::shadowNearPlane, nullptr},
    {"shadow_light_size", &Light::shadowLightSize, nullptr},
};

}  // namespace

py::dict lightToPython(const Light& light) {
    py::dict d;
    d["name"] = light.name;
    d["type"] = kLightTypes[int(light.type)];
    d["shadows"] = kLightShadows[int(light.shadows)];
    for (const LightField& field : kLightFields) {
        if (field.number) {
            d[field.key] = light.*field.number;
        } else {
            const glm::vec3& v = light.*field.vector;
            d[field.key] = py::make_tuple(v.x, v.y, v.z);
        }
    }
    return d;
}

Light lightFromPython(const py::handle& values, Light light, const std::string& what) {
    if (!py::isinstance<py::dict>(values)) throw Error(what + ": expected a dict of light keys (got " + typeName(values) + ")");
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(values)) {
        const std::string name = py::str(key);
        const std::string label = what + " " + name;
        const auto field = std::find_if(std::begin(kLightFields), std::end(kLightFields),
                                        [&](const LightField& f) { return name == f.key; });
        if (field != std::end(kLightFields)) {
            if (field->number) light.*field->number = floatFromPython(value, label);
            else light.*field->vector = vec3FromPython(value, label);
        } else if (name == "name") {
            light.name = py::str(value);
        } else if (name == "type") {
            light.type = LightType(choiceIndex(value, kLightTypes, label));
        } else if (name == "shadows") {
            light.shadows = LightShadows(choiceIndex(value, kLightShadows, label));
        } else {
            throw Error(what + ": unknown key '" + name + "'");
        }
    }
    const float length = glm::length(light.wsDirection);
    if (!(length > 1e-6f)) throw Error(what + " ws_direction must not be zero");
    light.wsDirection /= length;
    return light;
}

}  // namespace penumbra::python
