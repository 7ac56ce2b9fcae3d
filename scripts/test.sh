#!/usr/bin/env bash
# Builds and runs every test: CPU unit tests and GPU render tests on lavapipe (Mesa's CPU Vulkan
# driver) with the Vulkan validation layers on. Run scripts/setup.sh first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
export PENUMBRA_DEVICE=cpu
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 900
# The library as others use it: installed, found with find_package, embedded in a program.
bash scripts/test_embed.sh
