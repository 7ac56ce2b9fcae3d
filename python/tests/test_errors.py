"""Every bad input raises penumbra.Error with one line (the CLI's message where the CLI has one);
nothing crashes the interpreter."""
import numpy as np
import pytest

import penumbra
from conftest import DEVICE, cli_error, scene_path

W, H = 32, 18


def message(error_info):
    text = str(error_info.value)
    assert "\n" not in text
    return text


def test_missing_file_gives_the_cli_message(cli, tmp_path):
    missing = tmp_path / "missing.glb"
    with pytest.raises(penumbra.Error) as error:
        penumbra.load_scene(missing)
    assert message(error) == cli_error("render", missing, "-o", tmp_path / "out.png")


def test_bad_file_gives_the_cli_message(cli, tmp_path):
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "nodes": [{"mesh": 4}], "scenes": [{"nodes": [0]}]}')
    with pytest.raises(penumbra.Error) as error:
        penumbra.load_scene(str(bad))
    assert message(error) == cli_error("render", bad, "-o", tmp_path / "out.png")


@pytest.mark.parametrize("key,value,cli_value", [
    ("shadows.directional.filter", "PCF9x9", "PCF9x9"),
    ("shadows.directional.cascadeCount", 9, "9"),
    ("shadows.nope", 1, "1"),
    ("shadows.directional.cascadeCount", "two", "two"),
])
def test_bad_setting_gives_the_cli_message(cli, renderer_of, tmp_path, key, value, cli_value):
    expected = cli_error("render", scene_path("cube.gltf"), "--set", f"{key}={cli_value}", "-o", tmp_path / "o.png")
    with pytest.raises(penumbra.Error) as error:
        penumbra.validate_settings({key: value})
    assert message(error) == expected
    with pytest.raises(penumbra.Error) as error:
        renderer_of("cube.gltf").render(width=W, height=H, settings={key: value})
    assert message(error) == expected


@pytest.mark.parametrize("settings", [
    {"shadows.maxDistance": float("nan")}, {"shadows.maxDistance": object()}, {3: 1}, "PCF5x5",
    {"shadows": {"directional": {"filter": 5}}},
])
def test_settings_of_the_wrong_type_raise(settings):
    with pytest.raises(penumbra.Error):
        penumbra.validate_settings(settings)


def test_light_out_of_range(renderer_of):
    scene = penumbra.load_scene(scene_path("cube.gltf"))
    with pytest.raises(penumbra.Error, match=r"^light 3 does not exist \(the scene has 1 lights\)$"):
        renderer_of("cube.gltf").render(width=W, height=H, aov="shadow", light=3)
    with pytest.raises(penumbra.Error, match=r"^light 3 does not exist"):
        penumbra.reference(scene, W, H, light=3)
    with pytest.raises(penumbra.Error, match=r"^light 3 does not exist"):
        renderer_of("cube.gltf").set_light(3, {"intensity": 2.0})
    with pytest.raises(penumbra.Error, match="light must be an integer"):
        renderer_of("cube.gltf").render(width=W, height=H, aov="shadow", light=-1)


@pytest.mark.parametrize("arguments", [
    {"width": 0}, {"width": 20000}, {"height": -3}, {"width": 2.5}, {"aov": "normals"}, {"aov": 3},
    {"camera": {"position": (0, 1, 5)}}, {"camera": {"position": (0, 1, 5), "target": (0, 1, 5)}},
    {"camera": {"position": (0, 1, 5), "target": (0, 0, 0), "fov": 180}},
    {"camera": {"position": (0, 1, 5), "target": (0, 0, 0), "zoom": 2}},
    {"camera": {"position": "here", "target": (0, 0, 0)}}, {"camera": [0, 1, 5]},
    {"camera": {"position": (0, 1, float("nan")), "target": (0, 0, 0)}},
])
def test_bad_render_arguments_raise(renderer_of, arguments):
    with pytest.raises(penumbra.Error):
        renderer_of("cube.gltf").render(**{"width": W, "height": H, **arguments})


@pytest.mark.parametrize("positions,indices,error", [
    (np.zeros((3, 3), np.int32), np.array([[0, 1, 2]]), "positions must be a floating-point array"),
    (np.zeros((3, 2), np.float32), np.array([[0, 1, 2]]), "positions must be a floating-point array"),
    (np.zeros((3, 3, 1), np.float32), np.array([[0, 1, 2]]), "positions must be a floating-point array"),
    (np.zeros((3, 3), np.float32), np.array([[0.0, 1.0, 2.0]]), "indices must be an integer array"),
    (np.zeros((3, 3), np.float32), np.array([0, 1, 2, 0]), "indices must be an integer array"),
    (np.zeros((3, 3), np.float32), np.array([[0, 1, 3]]), "not from 0 to the vertex count"),
    (np.zeros((3, 3), np.float32), np.array([[0, -1, 2]]), "not from 0 to the vertex count"),
])
def test_scene_builder_refuses_bad_arrays(positions, indices, error):
    with pytest.raises(penumbra.Error, match=error):
        penumbra.SceneBuilder().add_mesh(positions, indices)


def test_scene_builder_refuses_bad_indices_and_values():
    builder = penumbra.SceneBuilder()
    with pytest.raises(penumbra.Error, match="mesh must be an integer from 0"):
        builder.add_instance(0)
    with pytest.raises(penumbra.Error, match="material must be an integer from 0 to 0"):
        builder.add_box((1, 1, 1), material=2)
    with pytest.raises(penumbra.Error, match="world_from_object must be a"):
        builder.add_instance(builder.add_box((1, 1, 1)), np.eye(3))
    with pytest.raises(penumbra.Error, match="type"):
        builder.add_light({"type": "laser"})
    with pytest.raises(penumbra.Error, match="unknown key"):
        builder.add_light({"colour": (1, 1, 1)})
    with pytest.raises(penumbra.Error, match="material color"):
        builder.add_material((1, 0, 0))
    builder.add_mesh(np.array([[0, 0, 0], [1, 0, 0], [0, np.inf, 0]], np.float32), np.array([0, 1, 2]))
    builder.add_instance(1)
    with pytest.raises(penumbra.Error, match="not finite"):
        builder.build()


@pytest.mark.parametrize("ours,truth,error", [
    (np.zeros((4, 4), np.int16), np.zeros((4, 4), np.float32), "ours must be a float32 or uint8 array"),
    (np.zeros((4, 4, 1), np.float32), np.zeros((4, 4), np.float32), "ours must be a float32 or uint8 array"),
    (np.zeros((4, 4), np.float32), np.zeros((4, 5), np.float32), "the rendered image is 4x4 but the reference image is 5x4"),
    (np.full((4, 4), 2.0, np.float32), np.zeros((4, 4), np.float32), "ours must hold values from 0 to 1"),
    (np.full((4, 4), np.nan, np.float32), np.zeros((4, 4), np.float32), "ours must hold values from 0 to 1"),
    (np.zeros((4, 4), np.float32), "truth", "truth must be a float32 or uint8 array"),
])
def test_compare_refuses_bad_arrays(ours, truth, error):
    with pytest.raises(penumbra.Error, match=error):
        penumbra.compare(ours, truth)


def test_compare_refuses_a_bad_mask_and_threshold():
    image = np.zeros((4, 4), np.float32)
    with pytest.raises(penumbra.Error, match="valid must have the reference's shape"):
        penumbra.compare(image, image, valid=np.ones((3, 4), bool))
    with pytest.raises(penumbra.Error, match="threshold"):
        penumbra.compare(image, image, threshold=1.5)


def test_bad_scene_edits_raise(renderer_of):
    renderer = renderer_of("cube.gltf")
    with pytest.raises(penumbra.Error, match="instance 99 does not exist"):
        renderer.set_instance_transform(99, np.eye(4))
    with pytest.raises(penumbra.Error, match="world_from_object must be finite"):
        renderer.set_instance_transform(0, np.full((4, 4), np.nan))
    with pytest.raises(penumbra.Error, match="node 'no such node' does not exist"):
        renderer.set_node_transform("no such node", np.eye(4))
    with pytest.raises(penumbra.Error, match="unknown key 'direction'"):
        renderer.set_light(0, {"direction": (0, -1, 0)})
    with pytest.raises(penumbra.Error, match="ws_direction must not be zero"):
        renderer.set_light(0, {"ws_direction": (0, 0, 0)})
    with pytest.raises(penumbra.Error, match="shadowStrength = -2 is out of range"):
        renderer.set_light(0, {"shadow_strength": -2.0})
    with pytest.raises(penumbra.Error, match="cast_shadows"):
        renderer.set_instance_cast_shadows(0, "yes")


def test_bad_devices_and_scenes_raise():
    with pytest.raises(penumbra.Error, match="^device 57: "):
        penumbra.Renderer(penumbra.load_scene(), device=57)
    with pytest.raises(penumbra.Error):
        penumbra.Renderer(penumbra.load_scene(), device="tpu")
    with pytest.raises(penumbra.Error, match="scene must be a penumbra.Scene"):
        penumbra.reference("scene.glb", W, H)
    with pytest.raises(penumbra.Error, match="source must be a path"):
        penumbra.load_scene(42)


def test_a_closed_renderer_raises():
    renderer = penumbra.Renderer(penumbra.load_scene(scene_path("cube.gltf")), device=DEVICE)
    with renderer:
        renderer.render(width=W, height=H)
    with pytest.raises(penumbra.Error, match="closed"):
        renderer.render(width=W, height=H)
    with pytest.raises(penumbra.Error, match="closed"):
        renderer.set_light(0, {})
    assert renderer.stats is None
