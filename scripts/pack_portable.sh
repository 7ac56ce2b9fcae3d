#!/usr/bin/env bash
# Packs the programs of a build (penumbra, penumbra-viewer) with the shared libraries they load, so
# that they run on another x86-64 Linux host that has a GPU driver but none of Penumbra's packages,
# e.g. a GPU server without package access (docs/gpu-hosts.md):
#   scripts/pack_portable.sh [BUILD_DIR] [DEST]        (defaults: build, .portable)
# DEST/bin holds the programs, DEST/lib every library they need but the C and C++ runtimes (the host's
# glibc and libstdc++ must be as new as the build machine's) and the Vulkan loader; DEST/loaders holds
# the Debian packages of the Vulkan and GL loaders (apt-get download), for hosts that lack them. Set
# PENUMBRA_PACK_LOADERS=0 to skip that download.
set -euo pipefail
build=${1:-build}
dest=${2:-.portable}
test -x "$build/penumbra" || { echo "pack_portable.sh: no $build/penumbra (build first: scripts/build.sh)" >&2; exit 1; }

rm -rf "$dest"
mkdir -p "$dest/bin" "$dest/lib" "$dest/loaders"
for program in "$build/penumbra" "$build/penumbra-viewer"; do
  [ -x "$program" ] && cp "$program" "$dest/bin/"
done

# The libraries each program resolves here, but for the runtimes every host has its own of, and
# the Vulkan loader, which must be the host's (it finds the host's driver).
for program in "$dest"/bin/*; do
  ldd "$program" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | while read -r library; do
    case "$(basename "$library")" in
      ld-linux*|libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libstdc++.so.*|libgcc_s.so.*|libvulkan.so.*) ;;
      *) cp -L "$library" "$dest/lib/" ;;
    esac
  done
done

if [ "${PENUMBRA_PACK_LOADERS:-1}" != 0 ]; then
  (cd "$dest/loaders" && apt-get download libvulkan1 libglvnd0 libgl1 libglx0 libegl1 libopengl0 >/dev/null) ||
    echo "pack_portable.sh: warning: the loader packages were not downloaded" >&2
fi
du -sh "$dest"
