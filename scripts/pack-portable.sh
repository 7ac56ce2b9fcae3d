#!/usr/bin/env bash
# Packs the programs built here for a Linux GPU host that has a Vulkan driver but no packages to
# install: every `penumbra*` program of BUILD_DIR (penumbra, penumbra-viewer, the test and bench
# programs), the shared libraries they load, and the Vulkan loader as a Debian package for hosts
# that lack one.
#   scripts/pack-portable.sh [BUILD_DIR [DEST]]    (defaults: build/ and .portable/ of this checkout)
# Run scripts/build.sh first. DEST is emptied, then holds:
#   bin/      the programs, without debug information
#   lib/      their libraries, except glibc, libstdc++, libgcc_s and the Vulkan loader: the host's own
#             are used, so they must be at least as new as this machine's (Debian 12: glibc 2.36, GCC 12)
#   loaders/  libvulkan1 (.deb) of this machine's architecture
# On the GPU host, in the folder that holds DEST (the .deb step once, as root, and only where
# `ldconfig -p | grep libvulkan` prints nothing):
#   for f in .portable/loaders/*.deb; do dpkg -x "$f" /; done; ldconfig
#   LD_LIBRARY_PATH=.portable/lib .portable/bin/penumbra devices
# If the loader finds no driver, name the driver's ICD file, e.g. for NVIDIA
#   export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
# The render tests read tests/ at the absolute path of the checkout that built them; elsewhere use
# the penumbra program (docs/gpu-hosts.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(realpath -m "${1:-$root/build}")
dest=$(realpath -m "${2:-$root/.portable}")
[ -d "$build" ] || { echo "pack-portable.sh: no build folder $build (run scripts/build.sh)" >&2; exit 1; }
case "$dest" in /|"$root"|"$build") echo "pack-portable.sh: refusing DEST $dest" >&2; exit 1 ;; esac

rm -rf "$dest"
mkdir -p "$dest/bin" "$dest/lib" "$dest/loaders"
find "$build" -maxdepth 3 -type f -perm -u+x -name 'penumbra*' ! -name '*.so*' -exec cp {} "$dest/bin/" \;
[ -n "$(ls -A "$dest/bin")" ] || { echo "pack-portable.sh: no penumbra programs in $build" >&2; exit 1; }
# Without their debug information the programs are a tenth of the size (what a device copy carries).
strip --strip-debug "$dest"/bin/*

for program in "$dest"/bin/*; do
    missing=$(ldd "$program" | grep 'not found' || true)
    if [ -n "$missing" ]; then
        echo "pack-portable.sh: $(basename "$program") needs libraries this machine lacks:" >&2
        echo "$missing" >&2
        exit 1
    fi
    ldd "$program" | awk '/=> \// {print $3}' | while read -r lib; do
        case "$(basename "$lib")" in
            # glibc, the C++ runtime and the Vulkan loader come from the host.
            ld-linux*|libc.so*|libm.so*|libmvec.so*|libdl.so*|libpthread.so*|librt.so*|libresolv.so*|libutil.so*) ;;
            libstdc++.so*|libgcc_s.so*|libvulkan.so*) ;;
            *) cp -L "$lib" "$dest/lib/" ;;
        esac
    done
done

# The loader package, fetched with a package index of its own so this machine's apt state is untouched.
lists=$(mktemp -d)
trap 'rm -rf "$lists"' EXIT
mkdir -p "$lists/partial"
arch=$(dpkg --print-architecture)
apt_options=(-o "APT::Architecture=$arch" -o "APT::Architectures=$arch" -o "Dir::State::Lists=$lists")
if apt-get "${apt_options[@]}" update >/dev/null 2>&1 &&
   (cd "$dest/loaders" && apt-get "${apt_options[@]}" download libvulkan1 >/dev/null 2>&1); then
    :
else
    echo "pack-portable.sh: warning: libvulkan1 not downloaded; the host needs its own Vulkan loader" >&2
fi
echo "pack-portable.sh: $(find "$dest/bin" -type f | wc -l) programs, $(find "$dest/lib" -type f | wc -l) libraries" \
     "in $dest ($(du -sh "$dest" | cut -f1))"
