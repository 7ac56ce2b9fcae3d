// The _penumbra extension module: penumbra.Error, devices, settings, the ray-traced reference and the
// shadow comparison; the scene and renderer classes come from scene_binding.cpp and
// renderer_binding.cpp. python/penumbra/__init__.py is the package users import.
#include <cmath>
#include <limits>
#include <string>

#include <penumbra/error.h>
#include <penumbra/reference.h>
#include <penumbra/settings_keys.h>
#include <penumbra/shadow_compare.h>
#include <penumbra/version.h>

#include "bindings.h"
#include "convert.h"

namespace penumbra::python {

namespace {

std::shared_ptr<Scene> sceneOf(const py::handle& source) {
    if (py::isinstance<PyRenderer>(source)) return source.cast<PyRenderer&>().scene();
    if (py::isinstance<Scene>(source)) return source.cast<std::shared_ptr<Scene>>();
    throw Error("scene must be a penumbra.Scene or a penumbra.Renderer (got " +
                std::string(py::str(py::type::of(source).attr("__name__"))) + ")");
}

// (shadow float32 (H, W) with NaN where no surface, valid bool (H, W), view depth float32 (H, W)).
py::tuple reference(const py::object& source, const py::object& width, const py::object& height,
                    const py::object& light, const py::object& settings, const py::object& camera,
                    const py::object& soft) {
    const std::shared_ptr<Scene> scene = sceneOf(source);
    const uint32_t w = checkedIndex(width, "width", 1, 16384), h = checkedIndex(height, "height", 1, 16384);
    const uint32_t lightIndex = checkedIndex(light, "light", 0, std::numeric_limits<uint32_t>::max());
    const uint32_t softSamples = checkedIndex(soft, "soft", 0, 4096);
    Settings userSettings = settingsFromPython(settings);
    const std::optional<Camera> lookAt = cameraFromPython(camera);
    ReferenceImages traced;
    {
        py::gil_scoped_release release;
        const CameraView view = cameraView(lookAt, *scene, w, h);
        applySceneDefaults(userSettings, *scene, view);
        traced = traceReferenceShadow(*scene, view, lightIndex, false, referenceOptionsFor(userSettings, view, softSamples));
    }
    py::array_t<float> shadow = shadowToPython(traced.shadow);
    py::array_t<bool> valid({size_t(h), size_t(w)});
    py::array_t<float> depth({size_t(h), size_t(w)});
    float* values = shadow.mutable_data();
    for (size_t p = 0; p < traced.viewDepth.size(); ++p) {
        if (std::isinf(traced.viewDepth[p])) values[p] = std::numeric_limits<float>::quiet_NaN();
        valid.mutable_data()[p] = traced.validMask.pixels[p] != 0;
        depth.mutable_data()[p] = traced.viewDepth[p];
    }
    return py::make_tuple(shadow, valid, depth);
}

Image validMaskFromPython(const py::handle& valid, const Image& nanMask) {
    Image mask(nanMask.width, nanMask.height, 1);
    if (valid.is_none()) {
        for (size_t p = 0; p < mask.pixels.size(); ++p) mask.pixels[p] = nanMask.pixels[p] ? 0 : 255;
        return mask;
    }
    const py::array array = py::module_::import("numpy").attr("asarray")(valid);
    const std::string kind = py::str(array.dtype().attr("kind"));
    if (array.ndim() != 2 || !(kind == "b" || kind == "u" || kind == "i"))
        throw Error("valid must be a bool array of shape (H, W) (got " + std::string(py::str(array.dtype())) + " with " +
                    std::to_string(array.ndim()) + " dimensions)");
    if (size_t(array.shape(0)) != mask.height || size_t(array.shape(1)) != mask.width)
        throw Error("valid must have the reference's shape (" + std::to_string(mask.height) + ", " +
                    std::to_string(mask.width) + ")");
    const py::array_t<bool, py::array::c_style | py::array::forcecast> flags(array);
    for (size_t p = 0; p < mask.pixels.size(); ++p) mask.pixels[p] = flags.data()[p] ? 255 : 0;
    return mask;
}

struct ComparedImages {
    Image ours, truth, valid;
};

ComparedImages comparedImages(const py::object& ours, const py::object& truth, const py::object& valid) {
    ComparedImages images;
    images.ours = shadowFromPython(ours, "ours", false, nullptr);
    Image nanMask;
    images.truth = shadowFromPython(truth, "truth", true, &nanMask);
    images.valid = validMaskFromPython(valid, nanMask);
    return images;
}

py::object compare(const py::object& ours, const py::object& truth, const py::object& valid, const py::object& threshold) {
    const ComparedImages images = comparedImages(ours, truth, valid);
    const float limit = floatFromPython(threshold, "threshold");
    return jsonToPython(toJson(compareShadowImages(images.ours, images.truth, images.valid, limit)));
}

py::object diffImage(const py::object& ours, const py::object& truth, const py::object& valid, const py::object& base) {
    const ComparedImages images = comparedImages(ours, truth, valid);
    Image dimBase;
    if (!base.is_none()) {
        const py::array array = py::module_::import("numpy").attr("asarray")(base);
        if (array.ndim() != 3 || (array.shape(2) != 3 && array.shape(2) != 4) || std::string(py::str(array.dtype())) != "uint8")
            throw Error("base must be a uint8 array of shape (H, W, 3) or (H, W, 4), e.g. a colour render");
        const py::array_t<uint8_t, py::array::c_style> pixels(array);
        dimBase = Image(uint32_t(array.shape(1)), uint32_t(array.shape(0)), 3);
        const size_t channels = size_t(array.shape(2));
        for (size_t p = 0; p < size_t(dimBase.width) * dimBase.height; ++p)
            for (size_t c = 0; c < 3; ++c) dimBase.pixels[p * 3 + c] = pixels.data()[p * channels + c];
    }
    return imageToPython(makeDiffImage(dimBase, images.ours, images.truth, images.valid), true);
}

py::list devices() {
    std::vector<DeviceInfo> list;
    {
        py::gil_scoped_release release;
        list = Device::list();
    }
    py::list result;
    for (const DeviceInfo& info : list) result.append(deviceInfoToPython(info));
    return result;
}

py::dict settingsReference() {
    const py::dict defaults = settingsToPython(Settings{});
    py::dict reference;
    for (const SettingKey& key : settingKeys()) {
        py::dict entry;
        entry["type"] = std::string(key.type == SettingType::Number ? "number" : key.type == SettingType::Integer ? "integer"
                                    : key.type == SettingType::PowerOfTwo ? "power of two" : key.type == SettingType::Bool ? "bool"
                                    : key.type == SettingType::Choice ? "choice" : "ratios");
        entry["allowed"] = key.allowed;
        entry["default"] = defaults.contains(key.key) ? py::object(defaults[py::str(key.key)]) : py::object(py::none());
        entry["description"] = key.description;
        reference[py::str(key.key)] = entry;
    }
    return reference;
}

}  // namespace

}  // namespace penumbra::python

PYBIND11_MODULE(_penumbra, m) {
    namespace py = pybind11;
    using namespace penumbra::python;
    m.doc() = "The compiled part of the penumbra package; import penumbra instead.";
    py::register_exception<penumbra::Error>(m, "Error", PyExc_RuntimeError);
    m.attr("__version__") = PENUMBRA_VERSION_STRING;
    bindScene(m);
    bindRenderer(m);
    m.def("devices", &devices, "The Vulkan devices Penumbra can use, in the order `device=N` counts them: "
                               "a list of {index, name, driver, cpu}.");
    m.def("default_settings", [] { return settingsToPython(penumbra::Settings{}); },
          "Every setting key with its default value, as a flat dict of dotted keys (docs/settings.md).");
    m.def("validate_settings", [](const py::object& settings) { return settingsToPython(settingsFromPython(settings)); },
          py::arg("settings"),
          "Every setting key's value once `settings` (dotted or nested keys) is applied to the defaults; raises "
          "penumbra.Error with the CLI's message for an unknown key, a wrong type or a value out of range.");
    m.def("settings_reference", &settingsReference,
          "Every setting key: {type, allowed, default, description}, the table docs/settings.md is made from.");
    m.def("_reference", &reference, py::arg("scene"), py::arg("width"), py::arg("height"), py::arg("light"),
          py::arg("settings"), py::arg("camera"), py::arg("soft"));
    m.def("_compare", &compare, py::arg("ours"), py::arg("truth"), py::arg("valid"), py::arg("threshold"));
    m.def("_diff_image", &diffImage, py::arg("ours"), py::arg("truth"), py::arg("valid"), py::arg("base"));
}
