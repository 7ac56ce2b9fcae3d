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

# scene -> (lights to compare, extra options). Directional scenes vary shadows.directional.filter, the
# spot/point scenes shadows.spot.filter (their "hard" lights ignore it).
SCENES = {
    "near_far_casters": ([0], ["--set", "shadows.maxDistance=150"]),
    "thin_wall": ([0], []),
    "poles": ([0], []),
    "grazing": ([0], []),
    "foliage": ([0], []),
    "low_sun": ([0], []),
    "far_field": ([0], ["--set", "shadows.maxDistance=150"]),
    "thin_slabs": ([0], []),
    "grazing_sun": ([0], []),
    "fence": ([0], []),
    "field_of_objects": ([0], []),
    "cube": ([0], []),
    "cad_engine": ([0], []),
    "spot_lights": ([0, 1], []),
    "spot_shelf": ([0, 1, 2], []),
    "point_light": ([0], []),
    "cad_engine_spot": ([0], []),
}
OTHER_LIGHT_SCENES = {"spot_lights", "spot_shelf", "point_light", "cad_engine_spot"}
FILTERS = ["PCF2x2", "PCF3x3", "PCF5x5", "PCF7x7"]


def row_command(args, scene, light, filter_name):
    lights, extra = SCENES[scene]
    key = "shadows.spot.filter" if scene in OTHER_LIGHT_SCENES else "shadows.directional.filter"
    command = [args.penumbra, "compare", os.path.relpath(os.path.join(HERE, scene + ".gltf")), "--light", str(light),
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
        if not os.path.exists(os.path.join(HERE, scene + ".gltf")):
            print(f"skipping {scene}: no tests/scenes/{scene}.gltf", file=sys.stderr)
            continue
        for light in SCENES[scene][0]:
            for filter_name in args.filters.split(","):
                command = row_command(args, scene, light, filter_name)
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
