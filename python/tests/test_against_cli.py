"""The package gives the pixels and numbers of the penumbra program for the same scene and settings."""
import json

import numpy as np
import pytest

import penumbra
from conftest import read_png, run_cli, scene_path, set_arguments

WIDTH, HEIGHT = 96, 54

# Canonical scenes, each with a light and settings of its own: a sun, an alpha-masked caster, spot
# lights, a point light.
SHADOW_CASES = [
    ("cube.gltf", 0, {"shadows.directional.filter": "PCF5x5"}),
    ("foliage.gltf", 0, {}),
    ("spot_lights.gltf", 1, {"shadows.spot.filter": "PCF3x3"}),
    ("point_light.gltf", 0, {}),
    ("near_far_casters.gltf", 0, {"shadows.maxDistance": 150, "shadows.directional.cascadeCount": 3}),
]


def levels(shadow):
    """A float shadow term as the 8-bit levels of the AOV PNG."""
    return np.rint(np.asarray(shadow, dtype=np.float64) * 255.0).astype(np.int32)


@pytest.mark.parametrize("name,light,settings", SHADOW_CASES, ids=[c[0] for c in SHADOW_CASES])
def test_shadow_aov_equals_the_cli_png(cli, renderer_of, tmp_path, name, light, settings):
    shadow = renderer_of(name).render(width=WIDTH, height=HEIGHT, aov="shadow", light=light, settings=settings)
    assert shadow.dtype == np.float32 and shadow.shape == (HEIGHT, WIDTH)
    png = tmp_path / "shadow.png"
    run_cli("render", scene_path(name), "--aov", "shadow", "--light", light, "--width", WIDTH, "--height", HEIGHT,
            "-o", png, *set_arguments(settings))
    expected = read_png(png).astype(np.int32)
    assert expected.shape == shadow.shape
    assert np.abs(levels(shadow) - expected).max() <= 1
    assert 0 < np.count_nonzero(expected < 128) < expected.size  # the scene shows a shadow


def test_colour_equals_the_cli_png(cli, renderer_of, tmp_path):
    rgba = renderer_of("cube.gltf").render(width=WIDTH, height=HEIGHT)
    assert rgba.dtype == np.uint8 and rgba.shape == (HEIGHT, WIDTH, 4)
    assert (rgba[..., 3] == 255).all()
    png = tmp_path / "colour.png"
    run_cli("render", scene_path("cube.gltf"), "--width", WIDTH, "--height", HEIGHT, "-o", png)
    expected = read_png(png).astype(np.int32)
    assert np.abs(rgba[..., :3].astype(np.int32) - expected).max() <= 1


@pytest.mark.parametrize("name,light", [("cube.gltf", 0), ("spot_shelf.gltf", 2)])
def test_reference_equals_the_cli(cli, tmp_path, name, light):
    truth = penumbra.reference(penumbra.load_scene(scene_path(name)), width=WIDTH, height=HEIGHT, light=light)
    run_cli("reference", scene_path(name), "--light", light, "--width", WIDTH, "--height", HEIGHT,
            "-o", tmp_path / "reference.png", "--mask", tmp_path / "mask.png")
    expected = read_png(tmp_path / "reference.png").astype(np.int32)
    surface = ~np.isnan(truth)
    assert 0 < surface.sum() < truth.size
    assert (levels(truth[surface]) == expected[surface]).all()
    assert (expected[~surface] == 255).all()
    assert (truth.valid == (read_png(tmp_path / "mask.png") != 0)).all()
    assert np.isinf(truth.view_depth[~surface]).all() and (truth.view_depth[surface] > 0).all()


def test_compare_equals_the_cli_json(cli, renderer_of):
    settings = {"shadows.directional.filter": "PCF3x3", "shadows.directional.cascadeCount": 2}
    shadow = renderer_of("cube.gltf").render(width=WIDTH, height=HEIGHT, aov="shadow", settings=settings)
    truth = penumbra.reference(renderer_of("cube.gltf"), width=WIDTH, height=HEIGHT, settings=settings)
    metrics = penumbra.compare(shadow, truth)
    done = run_cli("compare", scene_path("cube.gltf"), "--json", "--width", WIDTH, "--height", HEIGHT,
                   *set_arguments(settings))
    expected = json.loads(done.stdout)
    assert metrics.keys() == expected.keys()
    for key, value in expected.items():
        assert metrics[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    assert metrics["validPixels"] > 0 and metrics["edgePixels"] > 0


def test_stats_hold_the_cli_keys(cli, renderer_of, tmp_path):
    renderer = renderer_of("cube.gltf")
    renderer.render(width=WIDTH, height=HEIGHT)
    stats = renderer.stats
    run_cli("render", scene_path("cube.gltf"), "--width", WIDTH, "--height", HEIGHT, "-o", tmp_path / "c.png",
            "--stats", tmp_path / "stats.json")
    expected = json.loads((tmp_path / "stats.json").read_text())
    assert stats.keys() == expected.keys()
    assert stats["width"] == WIDTH and stats["device"]["name"] == expected["device"]["name"]
    assert stats["shadows"]["directional"]["tiles"] == expected["shadows"]["directional"]["tiles"]
