#!/usr/bin/env bash
# Installs every build, run and test dependency of Penumbra from Debian 12 packages.
# clang, its runtime (libFuzzer, ASan, UBSan) and llvm (llvm-symbolizer for readable sanitizer
# reports) serve the asan preset of CMakePresets.json: sanitizer tests and fuzzing.
# libjpeg62-turbo-dev: libturbojpeg0-dev's CMake package (libjpeg-turboTargets.cmake) names
# libjpeg.so.62, which only that package brings; a minimal Debian 12 lacks it and configure fails.
# ccache: rebuilds (and clones of the repository on one machine) reuse compiled objects.
# The Python package (python/, docs/python.md): pybind11 and NumPy for the module, pytest and
# Pillow (reads the CLI's PNGs) for its tests, Dask distributed and matplotlib for its examples;
# pip, setuptools, wheel and venv for `pip install --no-build-isolation .`; all for Debian's own
# /usr/bin/python3.
# Idempotent: packages already present are left alone. This is the only way dependencies arrive.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git ccache
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers glslc spirv-tools
  libspirv-cross-c-shared-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libcli11-dev
  libembree-dev libtbb-dev libglfw3-dev libimgui-dev libpng-dev libturbojpeg0-dev libjpeg62-turbo-dev libmeshoptimizer-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth xdotool
  clang libclang-rt-14-dev llvm
  assimp-testmodels
  python3-dev pybind11-dev python3-numpy python3-pytest python3-pil python3-distributed python3-matplotlib
  python3-pip python3-setuptools python3-wheel python3-venv
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all dependencies present"
fi
