#!/usr/bin/env bash
# Installs the built library into a temporary prefix, checks that the generated version header came
# with it, compiles an engine's shaders (tests/glsl/) against the installed shadow sampling GLSL, builds
# examples/embed against that copy (as a program outside the tree would, through find_package(penumbra)),
# runs it, and checks that its image equals `penumbra render` of the same scene and size; builds
# examples/own-renderer (an engine's own forward pass with ShadowSystem) the same way and checks that the
# shadow term its pass computes equals `penumbra render --aov shadow` on every canonical scene; when the
# build has the Python package, checks that it was installed under the prefix and imports from there.
# Run after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=$(mktemp -d)
work=$(mktemp -d)
trap 'rm -rf "$prefix" "$work"' EXIT
cmake --install build --prefix "$prefix" >/dev/null
test -f "$prefix/lib/pkgconfig/penumbra.pc"
# The generated version header is installed with the others, and holds the program's version.
version=$(./build/penumbra --version | cut -d' ' -f2)
grep -q "#define PENUMBRA_VERSION_STRING \"$version\"" "$prefix/include/penumbra/version.h"
# The installed shadow sampling (include/penumbra/shadows.glsl) compiles with the installed headers alone:
# an engine's shaders (tests/glsl/) include it with nothing of this tree on their include path.
for shader in tests/glsl/*.glsl; do
  name=$(basename "$shader" .glsl)
  glslc -fshader-stage="${name##*.}" --target-env=vulkan1.3 -I "$prefix/include" -o "$work/$name.spv" "$shader"
done
echo "shadow sampling: the installed penumbra/shadows.glsl compiles on its own ($(ls tests/glsl/*.glsl | wc -l) shaders)"
cmake -S examples/embed -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" -j "$(nproc)" >/dev/null
device=${PENUMBRA_DEVICE:-cpu}
"$work/build/penumbra_embed" "$work/embed.png" "$device" 320 180
./build/penumbra render --device "$device" --width 320 --height 180 -o "$work/cli.png"
./build/penumbra diff "$work/embed.png" "$work/cli.png" | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["maxAbsDifference"] == 0, "the embedded render differs from penumbra render: %s" % d
print("embed example: installed library renders the same image as penumbra render")'
# An engine's own renderer with Penumbra as its shadow system (docs/engine-integration.md): light 0's
# shadow term from its own forward pass (OUT.shadow.png) against penumbra render --aov shadow, validation
# on. Tolerance, as the other path-equality tests': at most 0.5 % of the pixels more than 1 level apart.
cmake -S examples/own-renderer -B "$work/own" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/own" -j "$(nproc)" >/dev/null
# own_equals_aov SCENE [--depth-prepass] [SETTING ...]: the example's shadow term against the AOV.
own_equals_aov() {
  local scene=$1 prepass=$2 name
  shift 2
  name=$(basename "${scene%.*}")$prepass
  local sets=() cli_sets=()
  for setting in "$@"; do sets+=(--set "$setting"); done
  if (($#)); then cli_sets=(--set "$@"); fi
  PENUMBRA_DEVICE=$device PENUMBRA_VALIDATION=1 "$work/own/penumbra_own_renderer" "$scene" "$work/own_$name.png" 128 72 \
    $prepass "${sets[@]}"
  ./build/penumbra render "$scene" --device "$device" --width 128 --height 72 --aov shadow "${cli_sets[@]}" \
    -o "$work/aov_$name.png" 2>/dev/null
  ./build/penumbra diff "$work/own_$name.shadow.png" "$work/aov_$name.png" | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["pixelsOver1"] <= 0.005 * d["pixels"], "%s: the own renderer'"'"'s shadow term differs from the shadow AOV: %s" % (sys.argv[1], d)' "$name"
}
scenes=0
for scene in tests/scenes/*.gltf tests/scenes/*.glb; do
  own_equals_aov "$scene" ""
  scenes=$((scenes + 1))
done
# The engine's own depth prepass handed to ShadowSystem (ShadowViewDepth): the tight cascade fit, and the
# virtual maps' page marking, read it.
for scene in poles foliage point_light; do
  own_equals_aov "tests/scenes/$scene.gltf" --depth-prepass
  own_equals_aov "tests/scenes/$scene.gltf" --depth-prepass shadows.directional.mode=virtual shadows.spot.mode=virtual
done
echo "own-renderer example: its shadow term equals penumbra render --aov shadow on $scenes canonical scenes, and with its own depth prepass (cascades and virtual maps) on 3"
# The Python package (docs/python.md), installed into its interpreter's site folder under the prefix.
module=$(find "$prefix" -name '_penumbra*.so' | head -n 1)
if [[ -n $module ]]; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)
  PYTHONPATH=$(dirname "$(dirname "$module")") "$python" -c '
import penumbra, sys
assert penumbra.__file__.startswith(sys.argv[1]) and penumbra.load_scene().triangle_count > 0
print("python package: installed under the prefix and importable (%s)" % penumbra.__file__)' "$prefix"
fi
