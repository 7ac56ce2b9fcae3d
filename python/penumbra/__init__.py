"""Penumbra: real-time shadow rendering on Vulkan, with its own ray-traced ground truth.

    import penumbra
    scene = penumbra.load_scene("scene.glb")          # a .gltf/.glb path, "gen:field:4:2", or None = the demo
    r = penumbra.Renderer(scene, device="auto")        # "auto" | "gpu" | "cpu" | an index of devices()
    rgba = r.render(width=640, height=360)             # uint8 (H, W, 4)
    shadow = r.render(width=640, height=360, aov="shadow", light=0)      # float32 (H, W), 1 lit .. 0 shadowed
    truth = penumbra.reference(scene, width=640, height=360, light=0)    # float32 (H, W), NaN where no surface
    metrics = penumbra.compare(shadow, truth)          # the keys of `penumbra compare --json`

Every error raises penumbra.Error with the one-line message the `penumbra` command prints.
docs/python.md has the whole API.
"""
from __future__ import annotations

import numpy as _np

from ._penumbra import (
    Error,
    Renderer,
    Scene,
    SceneBuilder,
    __version__,
    default_settings,
    devices,
    load_scene,
    settings_reference,
    validate_settings,
)
from . import _penumbra

for _public in (Error, Renderer, Scene, SceneBuilder):
    _public.__module__ = __name__
Error.__doc__ = """Every error of the package (a RuntimeError): one line, the message the `penumbra` command
prints after "penumbra: " for the same mistake (a missing file, a bad setting, a light that does not
exist), or one naming the argument and what it must be (a wrong array dtype or shape)."""

__all__ = [
    "Error", "Renderer", "Scene", "SceneBuilder", "ShadowTruth", "__version__", "compare", "default_settings",
    "devices", "diff_image", "load_scene", "reference", "settings_reference", "validate_settings",
]


class ShadowTruth(_np.ndarray):
    """The ray-traced shadow term of one light: a float32 (H, W) array, 1 lit .. 0 shadowed, NaN where the
    camera ray hits no surface; the values of `penumbra reference`'s PNG / 255.

    Extra attributes (None once the array is reshaped or sliced to another shape):
      valid       bool (H, W): the pixels a comparison counts (`penumbra reference --mask`);
      view_depth  float32 (H, W): view depth of the surface hit, +inf where none.
    np.asarray(truth) gives a plain ndarray view.
    """

    valid: _np.ndarray | None
    view_depth: _np.ndarray | None

    def __new__(cls, values, valid=None, view_depth=None):
        truth = _np.asarray(values, dtype=_np.float32).view(cls)
        truth.valid = valid
        truth.view_depth = view_depth
        return truth

    def __array_finalize__(self, source):
        for name in ("valid", "view_depth"):
            extra = getattr(source, name, None)
            setattr(self, name, extra if extra is not None and extra.shape == self.shape else None)

    def __reduce__(self):
        constructor, arguments, state = super().__reduce__()
        return constructor, arguments, (state, self.valid, self.view_depth)

    def __setstate__(self, state):
        array_state, self.valid, self.view_depth = state
        super().__setstate__(array_state)


def reference(scene, width=1280, height=720, *, light=0, settings=None, camera=None, soft=0) -> ShadowTruth:
    """Ray-traces light `light`'s exact shadow term with Embree, as `penumbra reference` does.

    scene: a Scene, or a Renderer (its scene with the edits made so far).
    settings, camera: as Renderer.render (the shadow distance and fade shape the truth too).
    soft: 0 = one shadow ray per pixel (a point light); N > 0 = the light as a disk of its
        shadow_light_size with N rays per pixel (the truth for 'pcss' lights; `--soft N`).
    Returns a ShadowTruth: float32 (H, W), NaN where no surface, with .valid and .view_depth.
    The GIL is released while it traces (on all cores).
    """
    values, valid, view_depth = _penumbra._reference(scene, width, height, light, settings, camera, soft)
    return ShadowTruth(values, valid, view_depth)


def _valid_of(truth, valid):
    return getattr(truth, "valid", None) if valid is None else valid


def compare(ours, truth, *, valid=None, threshold=0.5) -> dict:
    """Compares a rendered shadow term with the truth: the dict `penumbra compare --json` prints
    (validPixels, falseShadow, falseLit, misclassifiedPercent, edgeErrorPixels, meanAbsoluteError, ...).

    ours: float32 (H, W) in [0, 1] (render(aov="shadow")) or uint8 (H, W) (a `--aov shadow` PNG).
    truth: reference()'s result, or any such array (NaN = not compared).
    valid: bool (H, W), the pixels to count; default truth.valid, else every pixel that is not NaN.
    threshold: a pixel is lit when value >= threshold.
    """
    return _penumbra._compare(ours, truth, _valid_of(truth, valid), threshold)


def diff_image(ours, truth, *, valid=None, base=None) -> _np.ndarray:
    """The picture of `penumbra compare --diff`: uint8 (H, W, 4), false shadow red, false lit cyan, over
    `base` (a colour render, uint8 (H, W, 3 or 4); default the truth) dimmed."""
    return _penumbra._diff_image(ours, truth, _valid_of(truth, valid), base)
