#!/usr/bin/env bash
# Builds and runs every test (CI: .ci/run = setup + this, on 2 cores without a GPU; budget 40 minutes,
# measured times in README.md's testing section). Run scripts/setup.sh first. GPU tests run on
# lavapipe (Mesa's CPU Vulkan driver) with the Vulkan validation layers on. Two builds
# (CMakePresets.json), compiled through ccache when it is installed:
#   1. build/       RelWithDebInfo, everything scripts/build.sh makes plus the tests, the viewer and
#                   the benchmarks: the whole suite, then the installed library (scripts/test_embed.sh);
#   2. build-asan/  the asan preset: clang, ASan + UBSan + LSan (a leak fails), PENUMBRA_ASSERT and
#                   libstdc++'s assertions (what the debug preset checks) on: every unit test, the
#                   fuzz corpus replay (fuzz/corpus/), and the render tests where those checks add
#                   something (error and fallback paths, object lifetimes, a representative render of
#                   each path: the label "checked", chosen in tests/CMakeLists.txt).
# The debug preset stays for local debugging (-O0); its checks run here through the asan preset.
# PENUMBRA_TEST_STEPS=release or =asan runs one of the two.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
export PENUMBRA_DEVICE=cpu
steps=${PENUMBRA_TEST_STEPS:-release asan}
start=$(date +%s)
step() { echo "== scripts/test.sh: $* (at $(($(date +%s) - start)) s)"; }

if [[ " $steps " == *" release "* ]]; then
  step "release build"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build build -j "$jobs"
  step "release: whole suite"
  ctest --test-dir build --output-on-failure -j "$jobs" --timeout 600
  # The library as others use it: installed, found with find_package, embedded in a program.
  step "release: installed library"
  bash scripts/test_embed.sh
fi

if [[ " $steps " == *" asan "* ]]; then
  step "asan build"
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j "$jobs"
  step "asan: unit tests and fuzz corpus"
  ctest --preset asan -j "$jobs" -L 'unit|fuzz'
  step "asan: checked render tests"
  ctest --preset asan -j "$jobs" -L checked
fi
step "done"
