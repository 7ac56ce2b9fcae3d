#pragma once
// The penumbra module's classes and the functions that bind them, with their docstrings
// (python/penumbra/__init__.pyi repeats the signatures for editors).
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <pybind11/pybind11.h>

#include <penumbra/device.h>
#include <penumbra/renderer.h>
#include <penumbra/scene.h>

namespace penumbra::python {

namespace py = pybind11;

// A device and a renderer of one scene. The GIL is released while a frame renders or the depth is
// traced; one mutex serialises this renderer's calls from several Python threads.
class PyRenderer {
public:
    PyRenderer(const std::shared_ptr<Scene>& scene, const py::object& device, bool validation, bool spinWait);
    py::object render(const py::object& width, const py::object& height, const py::object& settings,
                      const py::object& aov, const py::object& light, const py::object& camera);
    py::object stats();
    py::dict deviceInfo();
    std::shared_ptr<Scene> scene();  // a copy, with the edits so far
    void setInstanceTransform(const py::object& instance, const py::object& worldFromObject);
    size_t setNodeTransform(const std::string& node, const py::object& worldFromObject);
    void setInstanceCastShadows(const py::object& instance, const py::object& castShadows);
    void setLight(const py::object& light, const py::object& values);
    void close();

private:
    void checkOpen() const;

    std::mutex mutex_;
    std::unique_ptr<Device> device_;
    std::unique_ptr<Renderer> renderer_;  // destroyed before device_ (close() and the member order)
    std::optional<FrameStats> lastStats_;
    glm::uvec2 lastSize_{0, 0};
    uint32_t validationMessagesSeen_ = 0;  // validation=True: the messages frames before this one made
};

DeviceOptions deviceOptionsFromPython(const py::handle& device, bool validation, bool spinWait = false);
py::dict deviceInfoToPython(const DeviceInfo& info);

void bindScene(py::module_& m);
void bindRenderer(py::module_& m);

namespace docs {

inline constexpr const char* kScene = R"doc(A scene: meshes placed as instances, materials, lights and an optional camera, in world space.

Made by load_scene() or SceneBuilder.build(). A Renderer takes its own copy; edit that copy through
the Renderer (set_instance_transform, set_light, ...) and read it back from Renderer.scene.)doc";
inline constexpr const char* kSceneSource = "The file or generator it was loaded from; '' for the demo scene and built scenes.";
inline constexpr const char* kSceneLights = R"doc(The lights as dicts, in KHR_lights_punctual order (the `light=` index):
name, type ('directional' | 'spot' | 'point'), color, intensity, range, inner_cone_angle and
outer_cone_angle (radians), ws_position, ws_direction (world space; the direction light travels),
shadows ('none' | 'hard' | 'soft' | 'pcss'), shadow_strength, shadow_bias, shadow_normal_bias,
shadow_near_plane, shadow_light_size.)doc";
inline constexpr const char* kSceneInstances = R"doc(The instances (one per glTF node and primitive) as dicts: mesh (index),
world_from_object (a (4, 4) float64 array, world = M @ [x, y, z, 1]), cast_shadows, node (the glTF
node's name) and ws_bounds ((min xyz, max xyz) in world space).)doc";
inline constexpr const char* kSceneCamera = R"doc(The scene's camera as a dict (name, world_from_view, position, fov in degrees,
near, far), or None when the renderer frames the scene automatically.)doc";
inline constexpr const char* kSceneBounds = "World-space bounds of every instance: ((min x, y, z), (max x, y, z)).";
inline constexpr const char* kSceneWarnings = "One line per thing skipped or added while loading (e.g. the default sun).";
inline constexpr const char* kSceneNodeInstances = "The indices of the instances of the glTF node named `node`.";

inline constexpr const char* kLoadScene = R"doc(Loads a scene.

source: a .gltf or .glb path (str or os.PathLike); "gen:field:N[:S]" or "gen:boxes:N" (the built-in
    scale scenes); None or "" for the built-in demo scene.
ground: put a grey ground plane under the scene (the CLI's --ground).
model: the glTF that gen:field copies. asset_root: the folder the scene's external files may come
    from (default: the scene file's folder; docs/security.md).
Raises penumbra.Error with the CLI's message for a missing or bad file.)doc";

inline constexpr const char* kSceneBuilder = R"doc(Builds a scene from NumPy arrays.

    b = penumbra.SceneBuilder()
    grey = b.add_material((0.8, 0.8, 0.8, 1.0))
    ground = b.add_plane(20.0, 20.0, material=grey)
    b.add_instance(ground)
    tri = b.add_mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]]))
    b.add_instance(tri, np.eye(4))
    b.add_light({"type": "directional", "ws_direction": (-0.3, -1.0, -0.2), "intensity": 3.0})
    b.set_camera(position=(4, 3, 6), target=(0, 0.5, 0), fov=45)
    scene = b.build()

Indices are checked as they are added; build() checks the whole scene (penumbra.Error names the first
bad value) and leaves the builder empty.)doc";
inline constexpr const char* kAddMaterial = R"doc(Adds a material; returns its index.

color: linear RGBA base colour. alpha_mode: 'opaque' | 'mask' | 'blend'. shadows: how it casts
shadows, 'on' | 'clip' | 'dither' | 'off'. unlit: KHR_materials_unlit. A scene without materials gets
a default one (index 0).)doc";
inline constexpr const char* kAddMesh = R"doc(Adds a triangle mesh; returns its index.

positions: float32/float64 (N, 3), object space. indices: integer (M, 3) or (3M,), counter-clockwise
front faces, each in [0, N). normals: float (N, 3), default area-weighted vertex normals. uvs: float
(N, 2). material: a material index. A wrong dtype or shape raises penumbra.Error.)doc";
inline constexpr const char* kAddInstance = R"doc(Places mesh `mesh` in the world; returns the instance index.

world_from_object: a (4, 4) array (world = M @ [x, y, z, 1]); None = identity. name: its node name
(Renderer.set_node_transform moves every instance of a node).)doc";
inline constexpr const char* kAddLight = R"doc(Adds a light from a dict of Scene.lights' keys (any subset; 'type' defaults
to 'directional'); returns its index, the `light=` of render and reference.)doc";
inline constexpr const char* kSetCamera = R"doc(Sets the scene's camera: world-space position and target, vertical field of
view in degrees, near and far plane distances (far may be infinite).)doc";
inline constexpr const char* kBuild = "Checks and returns the scene; the builder starts empty again.";

inline constexpr const char* kRenderer = R"doc(The real-time renderer of one scene on one Vulkan device.

    r = penumbra.Renderer(scene, device="auto")   # "auto" | "gpu" | "cpu" | an index of devices()
    rgba = r.render(width=640, height=360)         # uint8 (H, W, 4)

It holds its own copy of the scene; the set_* methods edit it between frames (only what changed is
uploaded). The GIL is released while a frame renders. close() (or a with block) frees the device
early; otherwise it goes with the object. validation=True turns on the Vulkan validation layers (as
the CLI's --validation): a frame that makes them report raises penumbra.Error. spin_wait=True waits for
the GPU by polling its fences instead of sleeping (DeviceOptions::spinWait: steadier CPU frame times,
one core busy while the GPU works).)doc";
inline constexpr const char* kRender = R"doc(Renders one frame and returns it as a NumPy array.

aov: 'color' -> uint8 (H, W, 4): the PNG `penumbra render` writes, RGB sRGB plus alpha 255;
     'shadow' -> float32 (H, W): light `light`'s shadow term, 1 lit .. 0 shadowed (the `--aov shadow`
         PNG / 255: strength and fades applied; 1 where nothing is visible);
     'cascades' -> uint8 (H, W, 4): the cascade each pixel samples, as `--aov cascades`;
     'depth' -> float32 (H, W): view depth (distance along the camera's forward axis) of the surface
         at each pixel centre, +inf where none; traced on the CPU with the camera rays of reference().
Row 0 is the top of the image. settings: a dict of setting keys (penumbra.default_settings()), applied
as the CLI's --set. camera: {'position', 'target', 'fov' (vertical, degrees), 'near', 'far'} in world
space; None = the scene's camera. Bad arguments raise penumbra.Error.)doc";
inline constexpr const char* kStats = R"doc(The last frame's stats as a dict (the keys of `penumbra render --stats`):
gpuMs per pass, cpuMs per phase, the shadow plan, warnings, ... and device, width, height; None before
the first frame.)doc";
inline constexpr const char* kRendererScene = "A copy of the renderer's scene with the edits made so far.";
inline constexpr const char* kSetInstanceTransform = R"doc(Moves instance `instance`: world_from_object is a (4, 4) array
(world = M @ [x, y, z, 1]). Takes effect from the next frame.)doc";
inline constexpr const char* kSetNodeTransform = R"doc(Sets world_from_object of every instance of the glTF node `node` (its
primitives); returns how many. Raises penumbra.Error when no instance has that node name.)doc";
inline constexpr const char* kSetLight = R"doc(Changes light `light`: `values` holds any of Scene.lights' keys, e.g.
{"ws_direction": (0.2, -1, 0.1), "shadow_strength": 0.8}; the others keep their values.)doc";

}  // namespace docs

}  // namespace penumbra::python
