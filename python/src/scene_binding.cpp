// penumbra.Scene, penumbra.load_scene and penumbra.SceneBuilder.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include <penumbra/error.h>
#include <penumbra/scene_builder.h>
#include <penumbra/scene_loading.h>

#include "bindings.h"
#include "convert.h"

namespace penumbra::python {

namespace {

py::tuple vec3Tuple(const glm::vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

py::dict instanceToPython(const Instance& instance) {
    py::dict d;
    d["mesh"] = instance.meshIndex;
    d["world_from_object"] = mat4ToPython(instance.worldFromObject);
    d["cast_shadows"] = instance.castShadows;
    d["node"] = instance.nodeName;
    d["ws_bounds"] = py::make_tuple(vec3Tuple(instance.wsBounds.min), vec3Tuple(instance.wsBounds.max));
    return d;
}

py::object cameraToPython(const std::optional<Camera>& camera) {
    if (!camera) return py::none();
    py::dict d;
    d["name"] = camera->name;
    d["world_from_view"] = mat4ToPython(camera->worldFromView);
    d["position"] = vec3Tuple(glm::vec3(camera->worldFromView[3]));
    d["fov"] = glm::degrees(camera->yfov);
    d["near"] = camera->zNear;
    d["far"] = camera->zFar;
    return d;
}

std::string sceneRepr(const Scene& scene) {
    size_t triangles = 0;
    for (const Instance& instance : scene.instances) triangles += scene.meshes[instance.meshIndex].indices.size() / 3;
    return "<penumbra.Scene '" + (scene.sourcePath.empty() ? std::string("demo") : scene.sourcePath) + "': " +
           std::to_string(scene.instances.size()) + " instances, " + std::to_string(triangles) + " triangles, " +
           std::to_string(scene.lights.size()) + " lights>";
}

std::shared_ptr<Scene> loadScenePython(const py::object& source, bool ground, const py::object& model,
                                       const py::object& assetRoot) {
    auto path = [](const py::object& value, const char* what) -> std::string {
        if (value.is_none()) return "";
        try {
            return py::str(py::module_::import("os").attr("fspath")(value));
        } catch (const py::error_already_set&) {
            throw Error(std::string(what) + " must be a path, a string or None");
        }
    };
    SceneSourceOptions options;
    const std::string sourceText = path(source, "source");
    if (!model.is_none()) options.model = path(model, "model");
    options.assetRoot = path(assetRoot, "asset_root");
    options.addGround = ground;
    py::gil_scoped_release release;
    return std::make_shared<Scene>(loadScene(sourceText, options));
}

// SceneBuilder with the checks that penumbra::SceneBuilder leaves to assertions: every index a
// caller passes exists.
class PySceneBuilder {
public:
    uint32_t addMaterial(const py::object& color, float metallic, float roughness, const std::string& alphaMode,
                         float alphaCutoff, bool doubleSided, bool unlit, const std::string& shadows,
                         bool receiveShadows, const std::string& name) {
        Material material;
        material.name = name;
        const std::vector<float> rgba = numbersFromPython(color, "material color (RGBA, linear)", 4);
        material.baseColorFactor = glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3]);
        material.metallic = metallic;
        material.roughness = roughness;
        material.alphaMode = choice<AlphaMode>(alphaMode, {"opaque", "mask", "blend"}, "material alpha_mode");
        material.alphaCutoff = alphaCutoff;
        material.doubleSided = doubleSided;
        material.unlit = unlit;
        material.shadows = choice<MaterialShadowMode>(shadows, {"on", "clip", "dither", "off"}, "material shadows");
        material.receiveShadows = receiveShadows;
        ++materials_;
        return builder_.addMaterial(material);
    }

    uint32_t addMesh(const py::object& positions, const py::object& indices, const py::object& normals,
                     const py::object& uvs, const py::object& material, const std::string& name) {
        const py::array_t<float> osPositions = floatRows(positions, "positions", 3);
        const size_t count = size_t(osPositions.shape(0));
        Mesh mesh;
        mesh.name = name;
        mesh.materialIndex = checkedIndex(material, "material", 0, int64_t(std::max<uint32_t>(materials_, 1)) - 1);
        mesh.indices = triangleIndices(indices, "indices", count);
        mesh.vertices.resize(count);
        for (size_t i = 0; i < count; ++i)
            mesh.vertices[i].osPosition = glm::vec3(osPositions.at(i, 0), osPositions.at(i, 1), osPositions.at(i, 2));
        if (!normals.is_none()) {
            const py::array_t<float> osNormals = floatRows(normals, "normals", 3);
            if (size_t(osNormals.shape(0)) != count) throw Error("normals must have one row per position");
            for (size_t i = 0; i < count; ++i)
                mesh.vertices[i].osNormal = glm::vec3(osNormals.at(i, 0), osNormals.at(i, 1), osNormals.at(i, 2));
        } else {
            computeNormals(mesh);
        }
        if (!uvs.is_none()) {
            const py::array_t<float> texcoords = floatRows(uvs, "uvs", 2);
            if (size_t(texcoords.shape(0)) != count) throw Error("uvs must have one row per position");
            for (size_t i = 0; i < count; ++i) mesh.vertices[i].uv = glm::vec2(texcoords.at(i, 0), texcoords.at(i, 1));
        }
        return addCheckedMesh(std::move(mesh));
    }

    uint32_t addBox(const py::object& halfExtents, const py::object& material) {
        return addCheckedMesh(makeBoxMesh(vec3FromPython(halfExtents, "half_extents"), materialIndex(material)));
    }
    uint32_t addPlane(float width, float depth, const py::object& material) {
        return addCheckedMesh(makePlaneMesh(glm::vec2(width, depth), materialIndex(material)));
    }
    uint32_t addSphere(float radius, const py::object& material) {
        return addCheckedMesh(makeSphereMesh(radius, materialIndex(material)));
    }

    uint32_t addInstance(const py::object& mesh, const py::object& worldFromObject, bool castShadows,
                         const std::string& name) {
        const uint32_t meshIndex = checkedIndex(mesh, "mesh", 0, int64_t(meshes_) - 1);
        const glm::mat4 transform = worldFromObject.is_none() ? glm::mat4(1.0f)
                                                               : mat4FromPython(worldFromObject, "world_from_object");
        return builder_.addInstance(meshIndex, transform, castShadows, name);
    }

    uint32_t addLight(const py::dict& values) {
        Light light;
        if (values.contains("type")) light = lightFromPython(py::dict(py::arg("type") = values["type"]), light, "light");
        if (light.type != LightType::Directional) {
            light.shadowNearPlane = 0.1f;  // the glTF extras' default for spot and point lights
            light.shadowLightSize = defaultShadowLightSize(light.type);
        }
        return builder_.addLight(lightFromPython(values, light, "light"));
    }

    void setCamera(const py::object& position, const py::object& target, float fovDegrees, float zNear, float zFar) {
        const py::dict camera(py::arg("position") = position, py::arg("target") = target, py::arg("fov") = fovDegrees,
                              py::arg("near") = zNear, py::arg("far") = zFar);
        builder_.setCamera(*cameraFromPython(camera));
    }

    std::shared_ptr<Scene> build() {
        auto scene = std::make_shared<Scene>(builder_.build());
        materials_ = meshes_ = 0;
        validateScene(*scene);
        return scene;
    }

private:
    template <typename Enum>
    static Enum choice(const std::string& value, std::initializer_list<const char*> names, const std::string& what) {
        int i = 0;
        std::string allowed;
        for (const char* name : names) {
            if (value == name) return Enum(i);
            allowed += (i++ ? ", " : "") + std::string(name);
        }
        throw Error(what + " = \"" + value + "\" is out of range (allowed " + allowed + ")");
    }

    uint32_t materialIndex(const py::object& material) {
        return checkedIndex(material, "material", 0, int64_t(std::max<uint32_t>(materials_, 1)) - 1);
    }

    uint32_t addCheckedMesh(Mesh mesh) {
        ++meshes_;
        return builder_.addMesh(std::move(mesh));
    }

    // Area-weighted vertex normals (a triangle's cross product is twice its area).
    static void computeNormals(Mesh& mesh) {
        std::vector<glm::vec3> sums(mesh.vertices.size(), glm::vec3(0.0f));
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
            const glm::vec3 n = glm::cross(mesh.vertices[b].osPosition - mesh.vertices[a].osPosition,
                                           mesh.vertices[c].osPosition - mesh.vertices[a].osPosition);
            for (uint32_t v : {a, b, c}) sums[v] += n;
        }
        for (size_t i = 0; i < sums.size(); ++i) {
            const float length = glm::length(sums[i]);
            mesh.vertices[i].osNormal = length > 0.0f ? sums[i] / length : glm::vec3(0.0f, 1.0f, 0.0f);
        }
    }

    SceneBuilder builder_;
    uint32_t materials_ = 0, meshes_ = 0;
};

}  // namespace

void bindScene(py::module_& m) {
    py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", docs::kScene)
        .def_property_readonly("source", [](const Scene& s) { return s.sourcePath; }, docs::kSceneSource)
        .def_property_readonly("lights", [](const Scene& s) {
            py::list lights;
            for (const Light& light : s.lights) lights.append(lightToPython(light));
            return lights;
        }, docs::kSceneLights)
        .def_property_readonly("instances", [](const Scene& s) {
            py::list instances;
            for (const Instance& instance : s.instances) instances.append(instanceToPython(instance));
            return instances;
        }, docs::kSceneInstances)
        .def_property_readonly("camera", [](const Scene& s) { return cameraToPython(s.camera); }, docs::kSceneCamera)
        .def_property_readonly("ws_bounds", [](const Scene& s) {
            return py::make_tuple(vec3Tuple(s.wsBounds.min), vec3Tuple(s.wsBounds.max));
        }, docs::kSceneBounds)
        .def_property_readonly("mesh_count", [](const Scene& s) { return s.meshes.size(); }, "Number of meshes.")
        .def_property_readonly("material_count", [](const Scene& s) { return s.materials.size(); }, "Number of materials.")
        .def_property_readonly("triangle_count", [](const Scene& s) {
            size_t triangles = 0;
            for (const Instance& instance : s.instances) triangles += s.meshes[instance.meshIndex].indices.size() / 3;
            return triangles;
        }, "Triangles of all instances together.")
        .def_property_readonly("warnings", [](const Scene& s) { return s.warnings; }, docs::kSceneWarnings)
        .def("node_instances", [](const Scene& s, const std::string& node) {
            std::vector<uint32_t> found;
            for (uint32_t i = 0; i < s.instances.size(); ++i)
                if (s.instances[i].nodeName == node) found.push_back(i);
            return found;
        }, py::arg("node"), docs::kSceneNodeInstances)
        .def("__repr__", &sceneRepr);

    m.def("load_scene", &loadScenePython, py::arg("source") = py::none(), py::kw_only(), py::arg("ground") = false,
          py::arg("model") = py::none(), py::arg("asset_root") = py::none(), docs::kLoadScene);

    py::class_<PySceneBuilder>(m, "SceneBuilder", docs::kSceneBuilder)
        .def(py::init<>())
        .def("add_material", &PySceneBuilder::addMaterial, py::arg("color") = py::make_tuple(0.8, 0.8, 0.8, 1.0),
             py::kw_only(), py::arg("metallic") = 0.0f, py::arg("roughness") = 1.0f, py::arg("alpha_mode") = "opaque",
             py::arg("alpha_cutoff") = 0.5f, py::arg("double_sided") = false, py::arg("unlit") = false,
             py::arg("shadows") = "on", py::arg("receive_shadows") = true, py::arg("name") = "", docs::kAddMaterial)
        .def("add_mesh", &PySceneBuilder::addMesh, py::arg("positions"), py::arg("indices"), py::kw_only(),
             py::arg("normals") = py::none(), py::arg("uvs") = py::none(), py::arg("material") = 0, py::arg("name") = "",
             docs::kAddMesh)
        .def("add_box", &PySceneBuilder::addBox, py::arg("half_extents"), py::kw_only(), py::arg("material") = 0,
             "Adds a box mesh centred on the origin with these half extents; returns its mesh index.")
        .def("add_plane", &PySceneBuilder::addPlane, py::arg("width"), py::arg("depth"), py::kw_only(),
             py::arg("material") = 0, "Adds an XZ plane at y = 0 facing +Y; returns its mesh index.")
        .def("add_sphere", &PySceneBuilder::addSphere, py::arg("radius"), py::kw_only(), py::arg("material") = 0,
             "Adds a sphere mesh centred on the origin; returns its mesh index.")
        .def("add_instance", &PySceneBuilder::addInstance, py::arg("mesh"), py::arg("world_from_object") = py::none(),
             py::kw_only(), py::arg("cast_shadows") = true, py::arg("name") = "", docs::kAddInstance)
        .def("add_light", &PySceneBuilder::addLight, py::arg("light"), docs::kAddLight)
        .def("set_camera", &PySceneBuilder::setCamera, py::arg("position"), py::arg("target"), py::arg("fov") = 45.0f,
             py::arg("near") = 0.1f, py::arg("far") = std::numeric_limits<float>::infinity(), docs::kSetCamera)
        .def("build", &PySceneBuilder::build, docs::kBuild);
}

}  // namespace penumbra::python
