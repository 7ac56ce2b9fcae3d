"""The package's surface: every public name documented and in the .pyi stub, the error type, devices."""
import ast
import pathlib

import numpy as np
import pytest

import penumbra

STUB = pathlib.Path(penumbra.__file__).with_name("__init__.pyi")


def stub_names():
    tree = ast.parse(STUB.read_text())
    names, methods = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        if isinstance(node, ast.ClassDef):
            methods[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        if isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return names, methods


def public_members(cls):
    return {name for name in dir(cls) if not name.startswith("_") and name not in dir(np.ndarray)}


def test_the_stub_names_every_public_name_and_member():
    names, methods = stub_names()
    assert set(penumbra.__all__) <= names
    for cls in (penumbra.Scene, penumbra.SceneBuilder, penumbra.Renderer, penumbra.ShadowTruth):
        assert public_members(cls) <= methods[cls.__name__] | {"valid", "view_depth"}, cls.__name__


def test_everything_public_has_a_docstring():
    for name in penumbra.__all__:
        item = getattr(penumbra, name)
        if callable(item):
            assert (item.__doc__ or "").strip(), name
    for cls in (penumbra.Scene, penumbra.SceneBuilder, penumbra.Renderer):
        for member in public_members(cls):
            assert (getattr(cls, member).__doc__ or "").strip(), f"{cls.__name__}.{member}"


def test_errors_are_one_type():
    assert issubclass(penumbra.Error, RuntimeError)
    assert penumbra.Error.__module__ == "penumbra"
    with pytest.raises(penumbra.Error):
        penumbra.load_scene("gen:nothing")


def test_devices_list_the_cli_devices(cli):
    from conftest import run_cli
    listed = [f"{d['index']}: {d['name']} ({d['driver']}){' [cpu]' if d['cpu'] else ''}" for d in penumbra.devices()]
    assert listed == run_cli("devices").stdout.splitlines()


def test_the_truth_keeps_its_mask_through_pickling():
    import pickle
    truth = penumbra.ShadowTruth(np.array([[0.0, 1.0], [np.nan, 1.0]]), np.array([[True, True], [False, False]]))
    copy = pickle.loads(pickle.dumps(truth))
    assert (copy.valid == truth.valid).all() and copy.dtype == np.float32
    assert truth[0:1].valid is None  # another shape: the mask no longer applies
    assert penumbra.compare(np.array([[0.0, 0.0], [1.0, 1.0]], np.float32), truth)["validPixels"] == 2
