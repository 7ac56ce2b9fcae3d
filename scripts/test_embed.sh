#!/usr/bin/env bash
# Installs the built library into a temporary prefix, checks that the generated version header came
# with it, compiles an engine's shaders (tests/glsl/) against the installed shadow sampling GLSL, builds examples/embed against that copy (as a program outside the tree would, through
# find_package(penumbra)), runs it, and checks that its image equals `penumbra render` of the same
# scene and size; when the build has the Python package, checks that it was installed under the prefix
# and imports from there. Run after scripts/build.sh.
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
# The Python package (docs/python.md), installed into its interpreter's site folder under the prefix.
module=$(find "$prefix" -name '_penumbra*.so' | head -n 1)
if [[ -n $module ]]; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)
  PYTHONPATH=$(dirname "$(dirname "$module")") "$python" -c '
import penumbra, sys
assert penumbra.__file__.startswith(sys.argv[1]) and penumbra.load_scene().triangle_count > 0
print("python package: installed under the prefix and importable (%s)" % penumbra.__file__)' "$prefix"
fi
