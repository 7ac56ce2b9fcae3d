"""The examples of examples/python/ at small sizes: the comparison figure, the dataset in one process,
and the dataset on a Dask LocalCluster of 2 workers (the same images; a worker killed mid-run still
leaves every frame once)."""
import json
import os
import signal
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from conftest import DEVICE, REPOSITORY, scene_path

EXAMPLES = REPOSITORY / "examples" / "python"
sys.path.insert(0, str(EXAMPLES))  # before any worker starts: spawned workers import make_dataset too

import make_dataset  # noqa: E402

FRAMES = 6
DATASET = {"frames": FRAMES, "width": 80, "height": 45, "objects": 10, "random_state": 3, "shard_size": 1,
           "local": False, "workers": 2, "scheduler": None}


def run_example(*arguments):
    done = subprocess.run([sys.executable, *[str(a) for a in arguments]], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    return done


def images_of(folder):
    return {name: np.asarray(Image.open(folder / name)) for name in sorted(os.listdir(folder))}


def test_compare_example_draws_the_figure(tmp_path):
    figure = tmp_path / "figure.png"
    done = run_example(EXAMPLES / "compare_shadow.py", scene_path("cube.gltf"), "--width", 96, "--height", 54,
                       "--set", "shadows.directional.filter=PCF5x5", "--device", DEVICE, "-o", figure)
    metrics = json.loads(done.stdout[:done.stdout.rindex("}") + 1])
    assert metrics["validPixels"] > 0
    drawn = np.asarray(Image.open(figure))
    assert drawn.shape[1] > 3 * 96 and drawn.std() > 10


@pytest.fixture(scope="module")
def single_process(tmp_path_factory):
    folder = tmp_path_factory.mktemp("single")
    done = run_example(EXAMPLES / "make_dataset.py", folder, "--local", "--frames", FRAMES, "--width", 80,
                       "--height", 45, "--objects", 10, "--random-state", 3, "--device", DEVICE)
    assert f"{FRAMES}/{FRAMES} frames" in done.stderr  # the progress bar
    images = images_of(folder)
    assert sorted(images) == sorted([f"image_{i:05d}.png" for i in range(FRAMES)] +
                                    [f"mask_{i:05d}.png" for i in range(FRAMES)])
    masks = [images[f"mask_{i:05d}.png"] for i in range(FRAMES)]
    assert all(0 < np.count_nonzero(mask < 128) < mask.size for mask in masks)  # every frame shows shadows
    assert not all((masks[0] == mask).all() for mask in masks[1:])  # frames differ
    return images


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with Client(cluster) as dask_client:
        yield dask_client
    cluster.close()


def test_dataset_on_dask_equals_one_process(client, single_process, tmp_path):
    rendered = make_dataset.make_dataset({**DATASET, "output": str(tmp_path), "device": "per-worker"}, client=client)
    assert rendered == list(range(FRAMES))
    distributed = images_of(tmp_path)
    assert distributed.keys() == single_process.keys()
    for name, image in distributed.items():
        assert (image == single_process[name]).all(), name


def test_a_killed_worker_has_its_frames_redone(client, single_process, tmp_path):
    killed = []

    def kill_a_busy_worker(shard):
        if killed:
            return
        busy = [address for address, keys in client.processing().items() if keys]
        pids = client.run(os.getpid, workers=busy[:1])
        for pid in pids.values():
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    rendered = make_dataset.make_dataset({**DATASET, "output": str(tmp_path), "device": "per-worker"}, client=client,
                                         on_shard_done=kill_a_busy_worker)
    assert killed, "no worker was busy when the first shard finished"
    assert rendered == list(range(FRAMES))  # every frame once: none lost, none twice
    distributed = images_of(tmp_path)  # no partial file left behind either
    assert distributed.keys() == single_process.keys()
    for name, image in distributed.items():
        assert (image == single_process[name]).all(), name
