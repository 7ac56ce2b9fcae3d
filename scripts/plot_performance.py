#!/usr/bin/python3
"""Plots and tables of docs/performance.md from the `penumbra bench --json` files of
bench/performance_sweep.sh (docs/bench/<device>/*.json).

    /usr/bin/python3 scripts/plot_performance.py docs/bench/h200 docs/bench/lavapipe

Writes docs/performance_<device>_triangles.png, docs/performance_<device>_objects.png and (for
`moving_N_F.json` runs: gen:boxes:N with --move-objects F) docs/performance_<device>_moving.png, and
prints the markdown tables. Needs Debian's python3-matplotlib (apt install python3-matplotlib); it is a
documentation tool, so scripts/setup.sh does not install it.
"""
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PASSES = ["shadows.directional", "shadows.other", "main"]
PHASES = ["plan", "culling", "upload", "record", "submit", "readback"]  # readback: absent (0) in older runs


def load(folder):
    runs = {}
    for path in glob.glob(os.path.join(folder, "*.json")):
        name = os.path.basename(path)[:-5]
        if re.fullmatch(r"(field_\d+_\d+|boxes_\d+|moving_\d+_[0-9.]+)", name):
            with open(path) as f:
                runs[name] = json.load(f)
    return runs


def series(runs, prefix):
    picked = [(r["scene"]["triangles"], r["scene"]["instances"], name, r) for name, r in runs.items()
              if name.startswith(prefix)]
    return sorted(picked)


def gpu(run, name):
    return run["passes"].get(name, {}).get("median_ms", 0.0)


def cpu(run, name):
    return run["cpu"].get(name, {}).get("median_ms", 0.0)


def cpu_total(run):
    return sum(cpu(run, name) for name in PHASES)


def moved_fraction(name):
    return float(name.split("_")[2])


def finish(fig, axes, label, xlabel, path):
    for ax, title in ((axes[0], "GPU ms per pass"), (axes[1], "CPU ms per phase")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_title(f"{label}: {title}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot(runs, label, out_prefix):
    if any(name.startswith("field_") for name in runs):
        plot_triangles(runs, label, out_prefix)
    plot_objects(runs, label, out_prefix)


def plot_triangles(runs, label, out_prefix):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for spots, style in (("16", "-"), ("0", "--")):
        rows = [r for r in series(runs, "field_") if r[2].endswith("_" + spots)]
        if not rows:
            continue
        x = [r[0] / 1e6 for r in rows]
        for name in PASSES:
            axes[0].plot(x, [gpu(r[3], name) for r in rows], style, marker="o", label=f"{name} ({spots} spots)")
        for name in ("plan", "culling", "record"):
            axes[1].plot(x, [cpu(r[3], name) for r in rows], style, marker="o", label=f"{name} ({spots} spots)")
    finish(fig, axes, label, "triangles (millions), gen:field:N[:16]", out_prefix + "_triangles.png")


def plot_objects(runs, label, out_prefix):
    rows = series(runs, "boxes_")
    if not rows:
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    x = [r[1] for r in rows]
    for name in PASSES[:1] + PASSES[2:]:
        axes[0].plot(x, [gpu(r[3], name) for r in rows], marker="o", label=name)
    for name in PHASES:
        axes[1].plot(x, [cpu(r[3], name) for r in rows], marker="o", label=name)
    axes[1].plot(x, [cpu_total(r[3]) for r in rows], "k-", marker="s", label="CPU total")
    finish(fig, axes, label, "objects (instances), gen:boxes:N", out_prefix + "_objects.png")

    moving = sorted((moved_fraction(name), r) for name, r in runs.items() if name.startswith("moving_"))
    if not moving:
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    x = [fraction for fraction, _ in moving]
    for name in PASSES[:1] + PASSES[2:]:
        axes[0].plot(x, [gpu(r, name) for _, r in moving], marker="o", label=name)
    for name in PHASES:
        axes[1].plot(x, [cpu(r, name) for _, r in moving], marker="o", label=name)
    axes[1].plot(x, [cpu_total(r) for _, r in moving], "k-", marker="s", label="CPU total")
    objects = moving[0][1]["scene"]["instances"]
    finish(fig, axes, label, f"fraction of {objects} objects moved per frame (--move-objects)", out_prefix + "_moving.png")


def table(runs, prefix):
    lines = ["| scene | triangles | objects | GPU directional | GPU spot/point | GPU main | GPU sum | CPU plan | "
             "CPU culling | CPU record | frame median / p95 | draws dir / spot |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for triangles, instances, name, r in series(runs, prefix):
        total = sum(gpu(r, p) for p in PASSES)
        atlases = r.get("atlases", {})
        draws = "%d / %d" % (atlases.get("shadows.directional", {}).get("draws", 0),
                             atlases.get("shadows.other", {}).get("draws", 0))
        lines.append("| `%s` | %.2fM | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f / %.1f | %s |" % (
            r["scene"]["source"], triangles / 1e6, instances, gpu(r, PASSES[0]), gpu(r, PASSES[1]), gpu(r, PASSES[2]),
            total, cpu(r, "plan"), cpu(r, "culling"), cpu(r, "record"), r["frame"]["median_ms"], r["frame"]["p95_ms"],
            draws))
    return "\n".join(lines)


def moving_table(runs):
    lines = ["| objects | moved per frame | CPU plan | CPU upload | CPU record | CPU total median / phases' p95 summed | GPU directional | "
             "GPU frame median / p95 |", "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for fraction, r in sorted((moved_fraction(name), r) for name, r in runs.items() if name.startswith("moving_")):
        objects = r["scene"]["instances"]
        p95 = sum(r["cpu"].get(name, {}).get("p95_ms", 0.0) for name in PHASES)
        lines.append("| %d | %g (%d) | %.3f | %.3f | %.3f | %.3f / %.3f | %.2f | %.2f / %.2f |" % (
            objects, fraction, int(round(fraction * objects)), cpu(r, "plan"), cpu(r, "upload"), cpu(r, "record"),
            cpu_total(r), p95, gpu(r, PASSES[0]), r["gpuFrame"]["median_ms"], r["gpuFrame"]["p95_ms"]))
    return "\n".join(lines)


def main():
    for folder in sys.argv[1:]:
        runs = load(folder)
        if not runs:
            continue
        device = os.path.basename(os.path.normpath(folder))
        label = next(iter(runs.values()))["device"]
        plot(runs, label, os.path.join("docs", f"performance_{device}"))
        print(f"### {label}\n")
        print(table(runs, "field_") + "\n")
        print(table(runs, "boxes_") + "\n")
        if any(name.startswith("moving_") for name in runs):
            print(moving_table(runs) + "\n")


if __name__ == "__main__":
    main()
