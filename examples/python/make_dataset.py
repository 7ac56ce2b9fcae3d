#!/usr/bin/env python3
"""Renders a synthetic dataset: colour images and their exact shadow masks (the ray-traced shadow term
of the sun), frame after frame of boxes and balls on a ground, each frame with its own layout, sun and
camera drawn from --random-state and the frame's index.

    OUTPUT/image_00000.png   the colour render, RGB
    OUTPUT/mask_00000.png    the exact shadow term: 0 shadowed .. 255 lit (255 where no surface)

By default the frames are rendered on a Dask LocalCluster of --workers processes; --scheduler ADDRESS
uses an existing cluster (OUTPUT must then be a folder every worker can write); --local renders in
this process without Dask. Each worker process holds one Renderer, on device index (worker number mod
the device count) unless --device says otherwise. Frames are sharded by index, --shard-size frames a
task; a worker that dies has its shards redone elsewhere, and a frame's files are written whole
(written aside, then renamed), so every frame is there once at the end whoever rendered it.

    PYTHONPATH=build/python python3 examples/python/make_dataset.py /tmp/shadows --frames 100 --workers 2
"""
import argparse
import glob
import math
import os
import sys
import time

import numpy as np
from PIL import Image

import penumbra

GROUND_HALF = 12.0   # the ground spans [-12, 12] x [-12, 12]
FIELD_HALF = 8.0     # objects stay within [-8, 8]: inside the ground, so the scene's bounds never change
# sphere: each frame's cascades follow from its own camera, so a frame is the same whichever frames a
# worker rendered before it (the tight fit measures the view's depth).
SETTINGS = {"shadows.directional.fit": "sphere", "shadows.directional.filter": "PCF3x3"}


def build_scene(random_state, objects):
    """The dataset's scene: a ground, `objects` boxes and balls of sizes drawn from `random_state`, a sun."""
    rng = np.random.default_rng([random_state, 2**31])
    builder = penumbra.SceneBuilder()
    ground = builder.add_material((0.55, 0.55, 0.5, 1.0))
    builder.add_instance(builder.add_plane(2 * GROUND_HALF, 2 * GROUND_HALF, material=ground), name="ground")
    heights = []
    for index in range(objects):
        material = builder.add_material((*rng.uniform(0.2, 0.9, 3), 1.0))
        if index % 3 == 2:
            radius = rng.uniform(0.3, 0.8)
            mesh, half_height = builder.add_sphere(radius, material=material), radius
        else:
            half = rng.uniform(0.2, 0.9, 3)
            mesh, half_height = builder.add_box(half, material=material), half[1]
        builder.add_instance(mesh, translation(0.0, half_height, 0.0), name=f"object{index}")
        heights.append(half_height)
    builder.add_light({"type": "directional", "ws_direction": (-0.3, -1.0, -0.2), "intensity": 3.0})
    return builder.build(), heights


def translation(x, y, z, yaw=0.0):
    m = np.eye(4)
    c, s = math.cos(yaw), math.sin(yaw)
    m[:3, :3] = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    m[:3, 3] = (x, y, z)
    return m


def frame_layout(random_state, index, heights):
    """Frame `index`'s object transforms, sun direction and camera, from (random_state, index) alone."""
    rng = np.random.default_rng([random_state, index])
    transforms = []
    for half_height in heights:  # standing on the ground, anywhere in the field, turned about +Y
        x, z = rng.uniform(-FIELD_HALF, FIELD_HALF, 2)
        transforms.append(translation(x, half_height, z, yaw=rng.uniform(0, 2 * math.pi)))
    azimuth, elevation = rng.uniform(0, 2 * math.pi), math.radians(rng.uniform(25, 70))
    sun = (-math.cos(elevation) * math.cos(azimuth), -math.sin(elevation), -math.cos(elevation) * math.sin(azimuth))
    orbit, height = rng.uniform(0, 2 * math.pi), rng.uniform(6.0, 10.0)
    camera = {"position": (15.0 * math.cos(orbit), height, 15.0 * math.sin(orbit)), "target": (0.0, 0.5, 0.0),
              "fov": 50.0}
    return transforms, sun, camera


def write_png(pixels, path):
    """Writes whole or not at all: a worker killed mid-write leaves only a hidden .tmp file."""
    folder, name = os.path.split(path)
    partial = os.path.join(folder, f".{name}.{os.getpid()}.tmp")
    Image.fromarray(pixels).save(partial, format="PNG")
    os.replace(partial, path)


class FrameRenderer:
    """One process's renderer of the dataset's scene, and how it renders and writes a frame."""

    def __init__(self, options, device):
        self.options = options
        self.scene, self.heights = build_scene(options["random_state"], options["objects"])
        self.renderer = penumbra.Renderer(self.scene, device=device)

    def render(self, index):
        transforms, sun, camera = frame_layout(self.options["random_state"], index, self.heights)
        for instance, transform in enumerate(transforms, start=1):  # instance 0 is the ground
            self.renderer.set_instance_transform(instance, transform)
        self.renderer.set_light(0, {"ws_direction": sun})
        size = {"width": self.options["width"], "height": self.options["height"], "camera": camera, "settings": SETTINGS}
        colour = self.renderer.render(**size)
        truth = penumbra.reference(self.renderer, **size)
        mask = np.where(np.isnan(truth), 255, np.rint(np.nan_to_num(truth, nan=1.0) * 255)).astype(np.uint8)
        output = self.options["output"]
        write_png(colour[..., :3], os.path.join(output, f"image_{index:05d}.png"))
        write_png(mask, os.path.join(output, f"mask_{index:05d}.png"))
        return index


def shards(frames, shard_size):
    return [list(range(start, min(start + shard_size, frames))) for start in range(0, frames, shard_size)]


class Progress:
    """A one-line progress bar on stderr."""

    def __init__(self, total, stream=sys.stderr):
        self.total, self.done, self.stream, self.start = total, 0, stream, time.monotonic()

    def advance(self, count):
        self.done += count
        filled = 30 * self.done // max(self.total, 1)
        rate = self.done / max(time.monotonic() - self.start, 1e-9)
        self.stream.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} frames, {rate:.1f}/s")
        if self.done >= self.total:
            self.stream.write("\n")
        self.stream.flush()


def render_local(options, progress, on_shard_done=None):
    """Every frame in this process, with one renderer; returns the indices rendered, in order."""
    frame_renderer = FrameRenderer(options, options["device"])
    rendered = []
    for shard in shards(options["frames"], options["shard_size"]):
        rendered += [frame_renderer.render(index) for index in shard]
        progress.advance(len(shard))
        if on_shard_done:
            on_shard_done(shard)
    frame_renderer.renderer.close()
    return rendered


# ---- Dask: a worker plugin holds each worker process's renderer; tasks are shards of frame indices.

class RendererPlugin:
    """Makes the worker's FrameRenderer when the worker starts (a restarted worker gets a new one)."""

    name = "penumbra-dataset"

    def __init__(self, options):
        self.options = options
        self.frame_renderer = None

    def setup(self, worker):
        device = self.options["device"]
        if device == "per-worker":
            count = len(penumbra.devices())
            number = worker.name if isinstance(worker.name, int) else sum(map(ord, str(worker.name)))
            device = number % count if count else "auto"
        self.frame_renderer = FrameRenderer(self.options, device)

    def teardown(self, worker):
        if self.frame_renderer:
            self.frame_renderer.renderer.close()


def render_shard(shard):
    from distributed import get_worker

    frame_renderer = get_worker().plugins[RendererPlugin.name].frame_renderer
    return [frame_renderer.render(index) for index in shard]


def render_distributed(client, options, progress, on_shard_done=None):
    """Every frame on the cluster of `client`; returns the indices rendered, in order."""
    from distributed import as_completed

    client.register_worker_plugin(RendererPlugin(options), name=RendererPlugin.name)
    futures = [client.submit(render_shard, shard, key=f"penumbra-frames-{shard[0]}-{shard[-1]}", retries=2)
               for shard in shards(options["frames"], options["shard_size"])]
    rendered = []
    for future in as_completed(futures):
        shard = future.result()
        rendered += shard
        progress.advance(len(shard))
        if on_shard_done:
            on_shard_done(shard)
    return sorted(rendered)


def make_dataset(options, client=None, on_shard_done=None, progress_stream=sys.stderr):
    """Renders options["frames"] frames into options["output"]: in this process when options["local"],
    else on `client` (a distributed.Client) or a LocalCluster of options["workers"]. Returns the frame
    indices rendered (each once)."""
    os.makedirs(options["output"], exist_ok=True)
    progress = Progress(options["frames"], progress_stream)
    if options["local"]:
        rendered = render_local(options, progress, on_shard_done)
    elif client is not None:
        rendered = render_distributed(client, options, progress, on_shard_done)
    else:
        from distributed import Client, LocalCluster

        address = options.get("scheduler")
        cluster = None if address else LocalCluster(n_workers=options["workers"], threads_per_worker=1,
                                                    processes=True, dashboard_address=None)
        with Client(address or cluster) as own_client:
            rendered = render_distributed(own_client, options, progress, on_shard_done)
        if cluster:
            cluster.close()
    for partial in glob.glob(os.path.join(options["output"], ".*.tmp")):  # left by a worker that died
        os.remove(partial)
    return rendered


def parse_arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="the folder the images and masks go to")
    parser.add_argument("--frames", type=int, default=16)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--objects", type=int, default=12)
    parser.add_argument("--random-state", type=int, default=1, help="draws the dataset: the same number, the same frames")
    parser.add_argument("--shard-size", type=int, default=4, help="frames per task")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--local", action="store_true", help="render in this process, without Dask")
    where.add_argument("--workers", type=int, default=2, help="processes of the LocalCluster (default 2)")
    where.add_argument("--scheduler", help="the address of an existing Dask scheduler, e.g. tcp://10.0.0.5:8786")
    parser.add_argument("--device", default=None,
                        help="auto | gpu | cpu | an index (default: auto locally, per-worker on Dask)")
    arguments = parser.parse_args(argv)
    if arguments.frames < 1 or arguments.shard_size < 1 or arguments.objects < 1:
        parser.error("--frames, --shard-size and --objects must be at least 1")
    options = vars(arguments)
    if options["device"] is None:
        options["device"] = "auto" if arguments.local else "per-worker"
    return options


def main(argv=None):
    options = parse_arguments(argv)
    try:
        rendered = make_dataset(options)
    except penumbra.Error as error:
        raise SystemExit(f"make_dataset: {error}")
    print(f"{len(rendered)} frames in {options['output']}")


if __name__ == "__main__":
    main()
