#!/usr/bin/env python3
"""Renders a scene's shadow term and its ray-traced truth, and draws them side by side with the error
pixels (false shadow red, false lit cyan), as `penumbra compare --diff` measures them.

    PYTHONPATH=build/python python3 examples/python/compare_shadow.py tests/scenes/poles.gltf \
        --set shadows.directional.filter=PCF5x5 -o poles.png
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402

import penumbra  # noqa: E402


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", nargs="?", default=None, help="a .gltf/.glb, gen:..., or nothing for the demo scene")
    parser.add_argument("--light", type=int, default=0, help="the light whose shadow is compared")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a setting, as the CLI's --set")
    parser.add_argument("--device", default="auto", help="auto | gpu | cpu | an index")
    parser.add_argument("-o", "--output", default="compare.png", help="the figure (PNG)")
    return parser.parse_args()


def settings_from(assignments):
    """--set KEY=VALUE pairs as a settings dict (values as JSON when they parse, else strings)."""
    settings = {}
    for assignment in assignments:
        key, _, value = assignment.partition("=")
        try:
            settings[key.strip()] = json.loads(value)
        except ValueError:
            settings[key.strip()] = value.strip()
    return settings


def main():
    arguments = parse_arguments()
    settings = settings_from(arguments.set)
    scene = penumbra.load_scene(arguments.scene)
    size = {"width": arguments.width, "height": arguments.height}
    with penumbra.Renderer(scene, device=arguments.device) as renderer:
        colour = renderer.render(**size, settings=settings)
        shadow = renderer.render(**size, settings=settings, aov="shadow", light=arguments.light)
    truth = penumbra.reference(scene, **size, light=arguments.light, settings=settings)
    metrics = penumbra.compare(shadow, truth)
    errors = penumbra.diff_image(shadow, truth, base=colour)

    figure, axes = plt.subplots(1, 3, figsize=(15, 15 * arguments.height / arguments.width / 3 + 0.8))
    panels = [(shadow, "rendered shadow term"), (truth, "ray-traced truth (grey: no surface)"),
              (errors, f"errors: {metrics['misclassifiedPercent']:.2f} % misclassified")]
    grey = plt.get_cmap("gray").copy()
    grey.set_bad("0.5")  # NaN: no surface
    for axis, (image, title) in zip(axes, panels):
        axis.imshow(image, cmap=grey, vmin=0.0, vmax=1.0, interpolation="nearest")
        axis.set_title(title)
        axis.axis("off")
    figure.tight_layout()
    figure.savefig(arguments.output, dpi=100)
    print(json.dumps(metrics, indent=2, sort_keys=True))
    print(f"wrote {arguments.output}")


if __name__ == "__main__":
    try:
        main()
    except penumbra.Error as error:
        raise SystemExit(f"compare_shadow: {error}")
