#!/usr/bin/env bash
# Configures build/ (RelWithDebInfo) and builds what the quick start runs: the library and the
# penumbra program. Run scripts/setup.sh first. `bash scripts/build.sh all` builds every target
# (tests, penumbra-viewer, benchmarks); other arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(--target penumbra)
if [[ ${1:-} == all ]]; then targets=(); shift; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
cmake --build build -j "$(nproc)" "${targets[@]}"
