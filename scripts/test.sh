#!/usr/bin/env bash
# Builds and runs every test (CI: .ci/run = setup + this, on 2 cores without a GPU). Run
# scripts/setup.sh first. GPU tests run on lavapipe (Mesa's CPU Vulkan driver) with the Vulkan
# validation layers on. Three builds (CMakePresets.json):
#   1. build/        RelWithDebInfo, what scripts/build.sh makes: the whole suite, then the installed
#                    library (scripts/test_embed.sh);
#   2. build-debug/  the debug preset, every PENUMBRA_ASSERT and libstdc++ assertion active: the whole
#                    suite again;
#   3. build-asan/   the asan preset (clang, ASan + UBSan + LSan, a leak fails): the unit tests, the
#                    render tests that exercise error and fallback paths, and a replay of the fuzz
#                    corpus (fuzz/corpus/).
# Set CMAKE_CXX_COMPILER_LAUNCHER=ccache in the environment to rebuild faster.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
export PENUMBRA_DEVICE=cpu
step() { echo "== scripts/test.sh: $* ($(date +%T))"; }

step "release build, whole suite"
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$jobs" --timeout 900
# The library as others use it: installed, found with find_package, embedded in a program.
bash scripts/test_embed.sh

step "debug preset (assertions on), whole suite"
cmake --preset debug >/dev/null
cmake --build --preset debug -j "$jobs"
ctest --preset debug -j "$jobs"

step "asan preset: unit tests, fuzz corpus replay, render tests of the error paths"
cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs"
asan_render_tests='^(DeviceFaults|CliErrors|CliRender|CliBench|CliReference)\.|^RenderTest\.(TextureOver|AtlasOver|OutputLarger|LightsBeyond|Degenerate|ZeroScale|SceneA|CameraView|SceneWith|LitPlane)'
ctest --preset asan -j "$jobs" -L 'unit|fuzz'
ctest --preset asan -j "$jobs" -R "$asan_render_tests"
step "done"
