"""Frames from Python: scenes built from arrays, scene edits between frames, the camera per call, the
depth AOV, no leak over 200 renders, and the GIL released while the renderer works."""
import ctypes
import gc
import os
import threading
import time

import numpy as np
import pytest

import penumbra
from conftest import DEVICE

W, H = 80, 45
SUN = {"type": "directional", "ws_direction": (0.5, -1.0, 0.2), "intensity": 3.0}
CAMERA = {"position": (4.0, 3.5, 5.0), "target": (0.0, 0.5, 0.0), "fov": 50.0}


def box_arrays(half):
    """A box's 8 corners and 12 counter-clockwise triangles, as NumPy arrays."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float64) * half
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    triangles = [(a, b, c) for a, b, c, d in faces] + [(a, c, d) for a, b, c, d in faces]
    return corners, np.array(triangles, np.int64)


def translation(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


@pytest.fixture(scope="module")
def built_scene():
    builder = penumbra.SceneBuilder()
    grey = builder.add_material((0.7, 0.7, 0.7, 1.0))
    builder.add_instance(builder.add_plane(30.0, 30.0, material=grey), name="ground")
    positions, indices = box_arrays(0.75)
    box = builder.add_mesh(positions.astype(np.float32), indices, material=grey, name="box")
    builder.add_instance(box, translation(0.0, 1.0, 0.0), name="box")
    builder.add_light(SUN)
    builder.set_camera(CAMERA["position"], CAMERA["target"], fov=CAMERA["fov"])
    return builder.build()


@pytest.fixture(scope="module")
def renderer(built_scene):
    with penumbra.Renderer(built_scene, device=DEVICE) as r:
        yield r


def shadowed(image):
    return int(np.count_nonzero(np.asarray(image) < 0.5))


def test_a_built_scene_renders_its_true_shadow(renderer, built_scene):
    assert built_scene.node_instances("box") == [1]
    assert len(built_scene.lights) == 1 and built_scene.triangle_count == 14
    shadow = renderer.render(width=W, height=H, aov="shadow")
    truth = penumbra.reference(built_scene, W, H)
    assert shadowed(truth) > 50
    metrics = penumbra.compare(shadow, truth)
    assert metrics["validPixels"] > W * H // 2
    assert metrics["interiorMisclassifiedPercent"] == 0.0
    assert metrics["misclassifiedPercent"] < 2.0


def test_frames_pass_the_validation_layers(built_scene, renderer):
    with penumbra.Renderer(built_scene, device=DEVICE, validation=True) as checked:
        for aov in ("color", "shadow", "cascades"):
            image = checked.render(width=W, height=H, aov=aov)
            assert (image == renderer.render(width=W, height=H, aov=aov)).all()


def test_a_renderer_that_spins_on_its_fences_draws_the_same_frames(built_scene, renderer):
    with penumbra.Renderer(built_scene, device=DEVICE, spin_wait=True) as spinning:
        for aov in ("color", "shadow"):
            assert (spinning.render(width=W, height=H, aov=aov) == renderer.render(width=W, height=H, aov=aov)).all()


def test_the_camera_per_call_equals_the_scene_camera(renderer, built_scene):
    own = renderer.render(width=W, height=H)
    given = renderer.render(width=W, height=H, camera=CAMERA)
    assert (own == given).all()
    elsewhere = renderer.render(width=W, height=H, camera={**CAMERA, "position": (-6.0, 4.0, 8.0)})
    assert (own != elsewhere).any()


def test_depth_is_the_view_depth_of_the_ground(renderer):
    depth = renderer.render(width=W, height=H, aov="depth", camera=CAMERA)
    assert depth.dtype == np.float32 and depth.shape == (H, W)
    position, target = np.array(CAMERA["position"]), np.array(CAMERA["target"])
    forward = (target - position) / np.linalg.norm(target - position)
    right = np.cross(forward, (0.0, 1.0, 0.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    tan_half = np.tan(np.radians(CAMERA["fov"]) / 2.0)
    checked = 0
    for py, px in [(H - 2, 3), (H - 5, W - 4), (H - 1, W // 2)]:  # bottom rows: the ground, row 0 is the top
        x = (2.0 * (px + 0.5) / W - 1.0) * tan_half * W / H
        y = (1.0 - 2.0 * (py + 0.5) / H) * tan_half
        direction = forward + x * right + y * up
        t = -position[1] / direction[1]  # ground plane y = 0
        assert depth[py, px] == pytest.approx(t * np.dot(direction, forward), rel=1e-4)
        checked += 1
    assert checked == 3
    sky = renderer.render(width=W, height=H, aov="depth", camera={**CAMERA, "target": (0.0, 50.0, 0.0)})
    assert np.isinf(sky).all()


def test_edits_between_frames(renderer, built_scene):
    before = renderer.render(width=W, height=H, aov="shadow")
    renderer.set_instance_transform(1, translation(100.0, 1.0, 0.0))
    assert shadowed(renderer.render(width=W, height=H, aov="shadow")) == 0
    assert shadowed(penumbra.reference(renderer, W, H)) == 0  # the reference sees the edited scene
    assert renderer.set_node_transform("box", translation(0.0, 1.0, 0.0)) == 1
    back = renderer.render(width=W, height=H, aov="shadow")
    # The shadow is back where the truth has it; not the same pixels as before: the scene's bounds keep
    # the far position, so the cascades are fitted differently and the filtered edges differ.
    assert shadowed(back) > 50
    assert penumbra.compare(back, penumbra.reference(renderer, W, H))["misclassifiedPercent"] < 1.0
    # The first frame after a move may still miss self-shadowing at the box's terminator (pixels the
    # reference excludes); from the second frame on the image is stable.
    before = renderer.render(width=W, height=H, aov="shadow")
    assert (renderer.render(width=W, height=H, aov="shadow") == before).all()

    renderer.set_instance_cast_shadows(1, False)
    assert shadowed(renderer.render(width=W, height=H, aov="shadow")) == 0
    renderer.set_instance_cast_shadows(1, True)

    renderer.set_light(0, {"ws_direction": (-0.2, -1.0, 0.6), "shadow_strength": 0.5})
    light = renderer.scene.lights[0]
    assert light["shadow_strength"] == 0.5 and light["intensity"] == SUN["intensity"]
    moved = renderer.render(width=W, height=H, aov="shadow")
    assert (moved != before).any() and moved.min() == pytest.approx(0.5, abs=1.0 / 255)
    renderer.set_light(0, built_scene.lights[0])
    renderer.render(width=W, height=H, aov="shadow")
    assert (renderer.render(width=W, height=H, aov="shadow") == before).all()


def resident_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def malloc_bytes():
    """Bytes malloc has handed out and not had back (glibc's mallinfo2): the C++ side's live memory."""
    class MallInfo2(ctypes.Structure):
        _fields_ = [(name, ctypes.c_size_t) for name in
                    ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks",
                     "keepcost")]
    libc = ctypes.CDLL(None)
    libc.mallinfo2.restype = MallInfo2
    info = libc.mallinfo2()
    return info.uordblks + info.hblkhd


def test_no_leak_over_200_renders(renderer):
    size = {"width": 64, "height": 36}  # 7 KB a colour frame, 2 KB a shadow frame
    for _ in range(20):
        renderer.render(**size)
        renderer.render(**size, aov="shadow")
    gc.collect()
    start_resident, start_malloc = resident_bytes(), malloc_bytes()
    for i in range(200):
        image = renderer.render(**size, aov="shadow" if i % 2 else "color")
        assert image.shape[0] == 36
        assert renderer.stats["width"] == 64
    del image
    gc.collect()
    grown_malloc, grown_resident = malloc_bytes() - start_malloc, resident_bytes() - start_resident
    # One frame's image kept per render would be 0.9 MB; the frame ring holds a few frames' stats.
    assert grown_malloc < 256_000, f"malloc'd memory grew by {grown_malloc} bytes over 200 renders"
    assert grown_resident < 2_500_000, f"resident memory grew by {grown_resident} bytes over 200 renders"


def spans_and_ticks(work):
    """Runs work() twice on another thread; returns its calls' (start, end) and this thread's ticks."""
    spans, finished = [], threading.Event()

    def worker():
        for _ in range(2):
            start = time.perf_counter()
            work()
            spans.append((start, time.perf_counter()))
        finished.set()

    thread = threading.Thread(target=worker)
    thread.start()
    stamps, last = [], 0.0
    while not finished.is_set():
        now = time.perf_counter()
        if now - last > 0.001:
            stamps.append(now)
            last = now
    thread.join()
    return spans, stamps


def test_the_gil_is_released_while_the_renderer_works(renderer, built_scene):
    """This thread runs in the middle of each call that another thread makes into the renderer."""
    calls = {"render": lambda scale: renderer.render(width=240 * scale, height=135 * scale),
             "depth": lambda scale: renderer.render(width=240 * scale, height=135 * scale, aov="depth"),
             "reference": lambda scale: penumbra.reference(built_scene, 240 * scale, 135 * scale)}
    margin = 0.02  # seconds: holding the GIL, a call lets other threads run only about its ends
    for name, work in calls.items():
        # Calls long enough to tell on any machine: the image grows until one takes 4 margins.
        for scale in (1, 2, 4, 8, 16):
            spans, stamps = spans_and_ticks(lambda: work(scale))
            if max(end - start for start, end in spans) > 4 * margin:
                break
        assert max(end - start for start, end in spans) > 4 * margin, f"{name}: calls too short to tell"
        inside = [t for t in stamps if any(start + margin < t < end - margin for start, end in spans)]
        assert inside, f"{name}: no other thread ran while it worked"
