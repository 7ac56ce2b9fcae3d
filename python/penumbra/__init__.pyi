"""Type stubs of the penumbra package (docs/python.md), for editors and type checkers."""
from os import PathLike
from typing import Any, Literal, Mapping, Sequence, TypedDict

import numpy as np
import numpy.typing as npt

__version__: str

Vec3 = Sequence[float] | npt.ArrayLike
Matrix4 = npt.ArrayLike  # (4, 4), rows first: world = M @ [x, y, z, 1]
SettingValue = float | int | bool | str | Sequence[float]
Settings = Mapping[str, SettingValue | Mapping[str, Any]]
Aov = Literal["color", "shadow", "cascades", "depth"]

class Error(RuntimeError):
    """Every error of the package: one line, the message the `penumbra` command prints."""

class Camera(TypedDict, total=False):
    position: Vec3  # world space; required
    target: Vec3  # world space; required
    fov: float  # vertical field of view in degrees, default 45
    near: float  # default 0.1
    far: float  # default infinity

class Light(TypedDict, total=False):
    name: str
    type: Literal["directional", "spot", "point"]
    color: Vec3
    intensity: float  # lux (directional) or candela (spot, point)
    range: float  # 0 = infinite
    inner_cone_angle: float  # radians
    outer_cone_angle: float  # radians
    ws_position: Vec3
    ws_direction: Vec3  # the direction the light travels
    shadows: Literal["none", "hard", "soft", "pcss"]
    shadow_strength: float
    shadow_bias: float
    shadow_normal_bias: float
    shadow_near_plane: float
    shadow_light_size: float

class Instance(TypedDict):
    mesh: int
    world_from_object: npt.NDArray[np.float64]
    cast_shadows: bool
    node: str
    ws_bounds: tuple[tuple[float, float, float], tuple[float, float, float]]

class DeviceInfo(TypedDict):
    index: int
    name: str
    driver: str
    cpu: bool

class Scene:
    """A scene: meshes placed as instances, materials, lights and an optional camera, in world space."""
    @property
    def source(self) -> str: ...
    @property
    def lights(self) -> list[Light]: ...
    @property
    def instances(self) -> list[Instance]: ...
    @property
    def camera(self) -> dict[str, Any] | None: ...
    @property
    def ws_bounds(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]: ...
    @property
    def mesh_count(self) -> int: ...
    @property
    def material_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    def node_instances(self, node: str) -> list[int]: ...

def load_scene(source: str | PathLike[str] | None = None, *, ground: bool = False,
               model: str | PathLike[str] | None = None, asset_root: str | PathLike[str] | None = None) -> Scene:
    """A .gltf/.glb path, "gen:field:N[:S]", "gen:boxes:N", or None for the demo scene."""

class SceneBuilder:
    """Builds a scene from NumPy arrays; build() checks it and returns it."""
    def __init__(self) -> None: ...
    def add_material(self, color: Sequence[float] = (0.8, 0.8, 0.8, 1.0), *, metallic: float = 0.0,
                     roughness: float = 1.0, alpha_mode: Literal["opaque", "mask", "blend"] = "opaque",
                     alpha_cutoff: float = 0.5, double_sided: bool = False, unlit: bool = False,
                     shadows: Literal["on", "clip", "dither", "off"] = "on", receive_shadows: bool = True,
                     name: str = "") -> int: ...
    def add_mesh(self, positions: npt.NDArray[np.floating], indices: npt.NDArray[np.integer], *,
                 normals: npt.NDArray[np.floating] | None = None, uvs: npt.NDArray[np.floating] | None = None,
                 material: int = 0, name: str = "") -> int: ...
    def add_box(self, half_extents: Vec3, *, material: int = 0) -> int: ...
    def add_plane(self, width: float, depth: float, *, material: int = 0) -> int: ...
    def add_sphere(self, radius: float, *, material: int = 0) -> int: ...
    def add_instance(self, mesh: int, world_from_object: Matrix4 | None = None, *, cast_shadows: bool = True,
                     name: str = "") -> int: ...
    def add_light(self, light: Light) -> int: ...
    def set_camera(self, position: Vec3, target: Vec3, fov: float = 45.0, near: float = 0.1,
                   far: float = ...) -> None: ...
    def build(self) -> Scene: ...

class Renderer:
    """The real-time renderer of one scene on one Vulkan device."""
    def __init__(self, scene: Scene, *, device: str | int = "auto", validation: bool = False,
                 spin_wait: bool = False) -> None: ...
    def render(self, *, width: int = 1280, height: int = 720, settings: Settings | None = None,
               aov: Aov = "color", light: int = 0, camera: Camera | None = None) -> np.ndarray:
        """color/cascades: uint8 (H, W, 4); shadow: float32 (H, W) 1 lit .. 0 shadowed; depth: float32 (H, W)."""
    @property
    def stats(self) -> dict[str, Any] | None: ...
    @property
    def device(self) -> DeviceInfo: ...
    @property
    def scene(self) -> Scene: ...
    def set_instance_transform(self, instance: int, world_from_object: Matrix4) -> None: ...
    def set_node_transform(self, node: str, world_from_object: Matrix4) -> int: ...
    def set_instance_cast_shadows(self, instance: int, cast_shadows: bool) -> None: ...
    def set_light(self, light: int, values: Light) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> Renderer: ...
    def __exit__(self, *exc: object) -> None: ...

class ShadowTruth(np.ndarray):
    """float32 (H, W): the ray-traced shadow term, NaN where no surface; .valid and .view_depth."""
    valid: npt.NDArray[np.bool_] | None
    view_depth: npt.NDArray[np.float32] | None

def reference(scene: Scene | Renderer, width: int = 1280, height: int = 720, *, light: int = 0,
              settings: Settings | None = None, camera: Camera | None = None, soft: int = 0) -> ShadowTruth: ...
def compare(ours: npt.ArrayLike, truth: npt.ArrayLike, *, valid: npt.ArrayLike | None = None,
            threshold: float = 0.5) -> dict[str, float | int]: ...
def diff_image(ours: npt.ArrayLike, truth: npt.ArrayLike, *, valid: npt.ArrayLike | None = None,
               base: npt.NDArray[np.uint8] | None = None) -> npt.NDArray[np.uint8]: ...
def devices() -> list[DeviceInfo]: ...
def default_settings() -> dict[str, SettingValue]: ...
def validate_settings(settings: Settings | None) -> dict[str, SettingValue]: ...
def settings_reference() -> dict[str, dict[str, Any]]: ...
