#!/usr/bin/env bash
# Two paths that must give one image, compared on a GPU (CI compares them on lavapipe): every scene of
# tests/scenes rendered with options A and with options B, and `penumbra diff` of each pair.
#   bench/compare_paths.sh PENUMBRA OUTDIR "OPTIONS A" "OPTIONS B" [WIDTH HEIGHT]
# e.g. "--main-view visibility --set render.meshletCulling=true" "--main-view visibility --set
# render.meshletCulling=false". Prints one line per scene: its name, then the diff's JSON (pixels,
# pixelsOver1, pixelsOver8, maxAbsDifference), then A's --stats meshletsSkipped.
set -euo pipefail
penumbra=${1:?usage: compare_paths.sh PENUMBRA OUTDIR "OPTIONS A" "OPTIONS B" [WIDTH HEIGHT]}
out=${2:?}; a=${3:?}; b=${4:?}; width=${5:-640}; height=${6:-360}
device=${PENUMBRA_DEVICE:-gpu}
mkdir -p "$out"
out=$(realpath "$out"); [[ "$penumbra" == */* ]] && penumbra=$(realpath "$penumbra")
cd "$(dirname "$0")/.."
for scene in tests/scenes/*.gltf tests/scenes/*.glb; do
    name=$(basename "$scene"); name=${name%.*}
    # shellcheck disable=SC2086
    "$penumbra" render "$scene" --device "$device" --width "$width" --height "$height" $a -o "$out/${name}_a.png" \
        --stats "$out/${name}_a.json" >/dev/null
    # shellcheck disable=SC2086
    "$penumbra" render "$scene" --device "$device" --width "$width" --height "$height" $b -o "$out/${name}_b.png" >/dev/null
    skipped=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1])).get('meshletsSkipped', ''))" "$out/${name}_a.json" 2>/dev/null || true)
    echo "$name $("$penumbra" diff "$out/${name}_a.png" "$out/${name}_b.png" | tail -n 1) $skipped"
done
