"""Shared fixtures of the penumbra package's tests (ctest's PythonPackage, label python).

Run from the repository root after building, with the interpreter CMake chose (it prints it):
    PENUMBRA_DEVICE=cpu XDG_RUNTIME_DIR=/tmp PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests
PENUMBRA_CLI names the `penumbra` program to compare with (default: the one of the same build).
Images are small (tens of pixels a side) so that the suite runs on lavapipe in well under 2 minutes.
"""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest
from PIL import Image

import penumbra

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
SCENES = REPOSITORY / "tests" / "scenes"
DEVICE = os.environ.get("PENUMBRA_DEVICE", "auto")


def _cli_path():
    configured = os.environ.get("PENUMBRA_CLI")
    if configured:
        return pathlib.Path(configured)
    # <build>/python/penumbra/__init__.py -> <build>/penumbra
    return pathlib.Path(penumbra.__file__).resolve().parents[2] / "penumbra"


CLI = _cli_path()


def scene_path(name):
    return str(SCENES / name)


def run_cli(*arguments, check=True):
    """Runs the penumbra program on the test device; returns the CompletedProcess (text)."""
    command = [str(CLI), *[str(a) for a in arguments]]
    if arguments and arguments[0] in ("render", "reference", "compare"):
        command += ["--device", DEVICE]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if check and done.returncode != 0:
        raise AssertionError(f"{' '.join(command)} failed: {done.stderr}")
    return done


def cli_error(*arguments):
    """The one-line message the program prints for a user error, without its "penumbra: " prefix."""
    done = run_cli(*arguments, check=False)
    assert done.returncode == 1, done
    line = done.stderr.strip().splitlines()[-1]
    assert line.startswith("penumbra: "), line
    return line[len("penumbra: "):]


def read_png(path):
    return np.asarray(Image.open(path))


def set_arguments(settings):
    """A settings dict as the CLI's --set arguments."""
    arguments = []
    for key, value in (settings or {}).items():
        arguments += ["--set", f"{key}={json.dumps(value) if not isinstance(value, str) else value}"]
    return arguments


@pytest.fixture(scope="session")
def cli():
    if not CLI.exists():
        pytest.fail(f"the penumbra program is missing at {CLI} (set PENUMBRA_CLI)")
    return CLI


_renderers = {}


@pytest.fixture(scope="session")
def renderer_of():
    """renderer_of(scene name) -> a Renderer of tests/scenes/<name>, one per scene for the session."""
    def make(name):
        if name not in _renderers:
            _renderers[name] = penumbra.Renderer(penumbra.load_scene(scene_path(name)), device=DEVICE)
        return _renderers[name]
    yield make
    for renderer in _renderers.values():
        renderer.close()
    _renderers.clear()
