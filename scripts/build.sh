#!/usr/bin/env bash
# Configures build/ (RelWithDebInfo) and builds what the quick start runs: the library, the
# penumbra program and, when configure found NumPy and pybind11, the Python package in build/python/
# (PYTHONPATH=build/python python3 -c "import penumbra"). Run scripts/setup.sh first.
# `bash scripts/build.sh all` builds every target (tests, penumbra-viewer, benchmarks); other
# arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(--target penumbra)
if [[ ${1:-} == all ]]; then targets=(); shift; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
# (grep reads the whole list: with -q it may stop early and pipefail would see cmake's SIGPIPE)
if ((${#targets[@]})) && cmake --build build --target help | grep -w penumbra_python >/dev/null; then
  targets+=(--target penumbra_python)
fi
cmake --build build -j "$(nproc)" "${targets[@]}"
