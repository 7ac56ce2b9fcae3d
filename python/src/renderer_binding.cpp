// penumbra.Renderer: one device and one real-time renderer of one scene; frames read back as arrays.
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <penumbra/error.h>
#include <penumbra/reference.h>
#include <penumbra/renderer.h>

#include "bindings.h"
#include "convert.h"

namespace penumbra::python {

namespace {

enum class Aov { Color, Shadow, Cascades, Depth };

Aov parseAov(const py::handle& value) {
    if (value.is_none()) return Aov::Color;
    const char* const names[] = {"color", "shadow", "cascades", "depth"};
    if (py::isinstance<py::str>(value)) {
        const std::string name = value.cast<std::string>();
        for (int i = 0; i < 4; ++i)
            if (name == names[i]) return Aov(i);
    }
    throw Error("aov = " + std::string(py::repr(value)) + " is out of range (allowed color, shadow, cascades, depth)");
}

py::array_t<float> depthToPython(const std::vector<float>& viewDepth, uint32_t width, uint32_t height) {
    py::array_t<float> array({size_t(height), size_t(width)});
    std::copy(viewDepth.begin(), viewDepth.end(), array.mutable_data());
    return array;
}

}  // namespace

DeviceOptions deviceOptionsFromPython(const py::handle& device, bool validation, bool spinWait) {
    DeviceOptions options;
    options.validation = validation;
    options.spinWait = spinWait;
    if (py::isinstance<py::str>(device)) options.device = device.cast<std::string>();
    else options.device = std::to_string(checkedIndex(device, "device", 0, 1023));
    return options;
}

py::dict deviceInfoToPython(const DeviceInfo& info) {
    py::dict d;
    d["index"] = info.index;
    d["name"] = info.name;
    d["driver"] = info.driver;
    d["cpu"] = info.isCpu;
    return d;
}

PyRenderer::PyRenderer(const std::shared_ptr<Scene>& scene, const py::object& device, bool validation, bool spinWait) {
    if (!scene) throw Error("Renderer: scene must be a penumbra.Scene (from load_scene or SceneBuilder.build)");
    const DeviceOptions options = deviceOptionsFromPython(device, validation, spinWait);
    Scene copy = *scene;
    py::gil_scoped_release release;
    try {
        device_ = std::make_unique<Device>(options);
    } catch (const Error& e) {
        if (options.device == "auto") throw;
        throw Error("device " + options.device + ": " + e.what());
    }
    renderer_ = std::make_unique<Renderer>(*device_, std::move(copy));
}

void PyRenderer::checkOpen() const {
    if (!renderer_) throw Error("this Renderer is closed");
}

py::object PyRenderer::render(const py::object& width, const py::object& height, const py::object& settings,
                              const py::object& aovName, const py::object& light, const py::object& camera) {
    RenderRequest request;
    request.width = checkedIndex(width, "width", 1, 16384);
    request.height = checkedIndex(height, "height", 1, 16384);
    request.aovLight = checkedIndex(light, "light", 0, std::numeric_limits<uint32_t>::max());
    const Aov aov = parseAov(aovName);
    request.output = aov == Aov::Shadow ? OutputMode::ShadowAov : aov == Aov::Cascades ? OutputMode::CascadesAov : OutputMode::Color;
    Settings frameSettings = settingsFromPython(settings);
    const std::optional<Camera> lookAt = cameraFromPython(camera);
    RenderResult result;
    std::vector<float> viewDepth;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(mutex_);
        checkOpen();
        const Scene& scene = renderer_->scene();
        const CameraView view = cameraView(lookAt, scene, request.width, request.height);
        std::vector<std::string> warnings = applySceneDefaults(frameSettings, scene, view);
        if (aov == Aov::Depth) {
            viewDepth = traceViewDepth(scene, view);
        } else {
            result = renderer_->render(request, frameSettings, view);
            result.stats.warnings.insert(result.stats.warnings.begin(), warnings.begin(), warnings.end());
            lastStats_ = std::move(result.stats);
            lastSize_ = {request.width, request.height};
        }
        // As the CLI's --validation: a frame that made the validation layer speak fails.
        const uint32_t messages = device_->validationMessageCount();
        if (messages > validationMessagesSeen_) {
            const uint32_t added = messages - validationMessagesSeen_;
            validationMessagesSeen_ = messages;
            throw Error(std::to_string(added) + " Vulkan validation messages (see above)");
        }
    }
    if (aov == Aov::Depth) return depthToPython(viewDepth, request.width, request.height);
    if (aov == Aov::Shadow) return shadowToPython(result.image);
    return imageToPython(result.image, true);
}

py::object PyRenderer::stats() {
    std::string json;
    DeviceInfo info;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!lastStats_ || !device_) return py::none();
        json = toJson(*lastStats_);
        info = device_->info();
    }
    py::dict stats = jsonToPython(json);
    stats["device"] = deviceInfoToPython(info);
    stats["width"] = lastSize_.x;
    stats["height"] = lastSize_.y;
    return stats;
}

py::dict PyRenderer::deviceInfo() {
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    return deviceInfoToPython(device_->info());
}

std::shared_ptr<Scene> PyRenderer::scene() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    return std::make_shared<Scene>(renderer_->scene());
}

void PyRenderer::setInstanceTransform(const py::object& instance, const py::object& worldFromObject) {
    const uint32_t index = checkedIndex(instance, "instance", 0, std::numeric_limits<uint32_t>::max());
    const glm::mat4 transform = mat4FromPython(worldFromObject, "world_from_object");
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    renderer_->setInstanceTransform(index, transform);
}

size_t PyRenderer::setNodeTransform(const std::string& node, const py::object& worldFromObject) {
    const glm::mat4 transform = mat4FromPython(worldFromObject, "world_from_object");
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    size_t moved = 0;
    const std::vector<Instance>& instances = renderer_->scene().instances;
    for (uint32_t i = 0; i < instances.size(); ++i) {
        if (instances[i].nodeName != node) continue;
        renderer_->setInstanceTransform(i, transform);
        ++moved;
    }
    if (moved == 0) throw Error("node '" + node + "' does not exist (no instance has that node name)");
    return moved;
}

void PyRenderer::setInstanceCastShadows(const py::object& instance, const py::object& castShadows) {
    const uint32_t index = checkedIndex(instance, "instance", 0, std::numeric_limits<uint32_t>::max());
    const bool cast = boolFromPython(castShadows, "cast_shadows");
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    renderer_->setInstanceCastShadows(index, cast);
}

void PyRenderer::setLight(const py::object& light, const py::object& values) {
    const uint32_t index = checkedIndex(light, "light", 0, std::numeric_limits<uint32_t>::max());
    Light current;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        checkOpen();
        const std::vector<Light>& lights = renderer_->scene().lights;
        if (index >= lights.size())
            throw Error("light " + std::to_string(index) + " does not exist (the scene has " +
                        std::to_string(lights.size()) + " lights)");
        current = lights[index];
    }
    const Light updated = lightFromPython(values, current, "light " + std::to_string(index));
    std::lock_guard<std::mutex> lock(mutex_);
    checkOpen();
    renderer_->setLight(index, updated);
}

void PyRenderer::close() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    renderer_.reset();  // before its device
    device_.reset();
}

void bindRenderer(py::module_& m) {
    py::class_<PyRenderer>(m, "Renderer", docs::kRenderer)
        .def(py::init<const std::shared_ptr<Scene>&, const py::object&, bool, bool>(), py::arg("scene"), py::kw_only(),
             py::arg("device") = "auto", py::arg("validation") = false, py::arg("spin_wait") = false)
        .def("render", &PyRenderer::render, py::kw_only(), py::arg("width") = 1280, py::arg("height") = 720,
             py::arg("settings") = py::none(), py::arg("aov") = "color", py::arg("light") = 0,
             py::arg("camera") = py::none(), docs::kRender)
        .def_property_readonly("stats", &PyRenderer::stats, docs::kStats)
        .def_property_readonly("device", &PyRenderer::deviceInfo, "The device it renders on: {index, name, driver, cpu}.")
        .def_property_readonly("scene", &PyRenderer::scene, docs::kRendererScene)
        .def("set_instance_transform", &PyRenderer::setInstanceTransform, py::arg("instance"),
             py::arg("world_from_object"), docs::kSetInstanceTransform)
        .def("set_node_transform", &PyRenderer::setNodeTransform, py::arg("node"), py::arg("world_from_object"),
             docs::kSetNodeTransform)
        .def("set_instance_cast_shadows", &PyRenderer::setInstanceCastShadows, py::arg("instance"),
             py::arg("cast_shadows"), "Whether instance `instance` casts shadows from the next frame on.")
        .def("set_light", &PyRenderer::setLight, py::arg("light"), py::arg("values"), docs::kSetLight)
        .def("close", &PyRenderer::close, "Frees the renderer and its device now; later calls raise penumbra.Error.")
        .def("__enter__", [](PyRenderer& self) -> PyRenderer& { return self; }, py::return_value_policy::reference)
        .def("__exit__", [](PyRenderer& self, const py::args&) { self.close(); });
}

}  // namespace penumbra::python
