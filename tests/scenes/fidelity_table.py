#!/usr/bin/env python3
"""Prints the fidelity table of docs/fidelity.md: every canonical scene x filter through `penumbra compare
--shimmer --json`, as a Markdown table (misclassified %, interior %, edge error px, edge balance, shimmer %),
each row with the exact command that produced it.

Usage: tests/scenes/fidelity_table.py [--penumbra build/penumbra] [--width 640 --height 360]
                                      [--atlas 2048] [--scenes a,b] [--filters PCF2x2,...] [--set key=value]...
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

# scene -> (file, [(light index, "sun" | "spot")], extra options). Sun rows vary
# shadows.directional.filter, spot/point rows shadows.spot.filter (their "hard" lights ignore it).
SCENES = {
    "near_far_casters": ("near_far_casters.gltf", [(0, "sun")], ["--set", "shadows.maxDistance=150"]),
    "thin_wall": ("thin_wall.gltf", [(0, "sun")], []),
    "poles": ("poles.gltf", [(0, "sun")], []),
    "grazing": ("grazing.gltf", [(0, "sun")], []),
    "foliage": ("foliage.gltf", [(0, "sun")], []),
    "low_sun": ("low_sun.gltf", [(0, "sun")], []),
    "far_field": ("far_field.gltf", [(0, "sun")], ["--set", "shadows.maxDistance=150"]),
    "thin_slabs": ("thin_slabs.gltf", [(0, "sun")], []),
    "grazing_sun": ("grazing_sun.gltf", [(0, "sun")], []),
    "fence": ("fence.gltf", [(0, "sun")], []),
    "field_of_objects": ("field_of_objects.gltf", [(0, "sun")], []),
    "cube": ("cube.gltf", [(0, "sun")], []),
    "cad_engine": ("cad_engine.glb", [(0, "sun"), (1, "spot")], []),
    "spot_lights": ("spot_lights.gltf", [(0, "spot"), (1, "spot")], []),
    "spot_shelf": ("spot_shelf.gltf", [(0, "spot"), (1, "spot"), (2, "spot")], []),
    "point_light": ("point_light.gltf", [(0, "spot")], []),
    "room_corner": ("room_corner.gltf", [(0, "spot")], []),
    "pcss_contact": ("pcss_contact.gltf", [(0, "sun"), (1, "spot")], ["--soft", "128"]),
}
FILTERS = ["PCF2x2", "PCF3x3", "PCF5x5", "PCF7x7"]


def row_command(args, scene, light, kind, filter_name):
    file, _, extra = SCENES[scene]
    key = "shadows.spot.filter" if kind == "spot" else "shadows.directional.filter"
    command = [args.penumbra, "compare", os.path.relpath(os.path.join(HERE, file)), "--light", str(light),
               "--width", str(args.width), "--height", str(args.height), "--device", args.device, "--json",
               "--set", f"shadows.directional.atlasSize={args.atlas}", "--set", f"shadows.spot.atlasSize={args.atlas}",
               "--set", f"{key}={filter_name}"] + extra
    if not args.no_shimmer:
        command.append("--shimmer")
    for assignment in args.set:
        command += ["--set", assignment]
    return command


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--penumbra", default="build/penumbra")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--atlas", type=int, default=2048)
    parser.add_argument("--device", default=os.environ.get("PENUMBRA_DEVICE", "cpu"))
    parser.add_argument("--scenes", default=",".join(SCENES))
    parser.add_argument("--filters", default=",".join(FILTERS))
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--no-shimmer", action="store_true")
    parser.add_argument("--commands", action="store_true", help="print each row's command under the table")
    args = parser.parse_args()

    print("| scene | light | filter | misclassified % | interior % | edge error px | edge balance | shimmer % |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    commands = []
    totals = []
    for scene in args.scenes.split(","):
        if not os.path.exists(os.path.join(HERE, SCENES[scene][0])):
            print(f"skipping {scene}: no tests/scenes/{SCENES[scene][0]}", file=sys.stderr)
            continue
        for light, kind in SCENES[scene][1]:
            for filter_name in args.filters.split(","):
                command = row_command(args, scene, light, kind, filter_name)
                run = subprocess.run(command, capture_output=True, text=True)
                if run.returncode != 0:
                    print(f"| {scene} | {light} | {filter_name} | failed: {run.stderr.strip()} |")
                    continue
                m = json.loads(run.stdout)
                shimmer = "-" if args.no_shimmer else "%.3f" % m["shimmerPercent"]
                print("| %s | %d | %s | %.3f | %.3f | %.2f | %+.2f | %s |" % (
                    scene, light, filter_name, m["misclassifiedPercent"], m["interiorMisclassifiedPercent"],
                    m["edgeErrorPixels"], m["edgeBalance"], shimmer), flush=True)
                totals.append((m["misclassifiedPercent"], m["interiorMisclassifiedPercent"],
                               m.get("shimmerPercent", 0.0)))
                commands.append(" ".join(shlex.quote(c) for c in command))
    if totals:
        n = len(totals)
        print("| **mean** | | | %.3f | %.3f | | | %s |" % (
            sum(t[0] for t in totals) / n, sum(t[1] for t in totals) / n,
            "-" if args.no_shimmer else "%.3f" % (sum(t[2] for t in totals) / n)))
    if args.commands:
        print()
        for c in commands:
            print("    " + c)


if __name__ == "__main__":
    main()
