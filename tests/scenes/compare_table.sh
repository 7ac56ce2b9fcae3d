#!/bin/sh
# Prints the compare table (scene x directional filter -> misclassified %, interior %, MAE) at the
# regression tests' resolution. Usage: tests/scenes/compare_table.sh [build/penumbra] [extra options]
set -e
penumbra=${1:-build/penumbra}
[ $# -gt 0 ] && shift
dir=$(dirname "$0")
printf '| scene | filter | misclassified %% | interior misclassified %% | MAE |\n| --- | --- | --- | --- | --- |\n'
for scene in near_far_casters thin_wall poles grazing foliage low_sun; do
    extra=""
    [ "$scene" = near_far_casters ] && extra="--set shadows.maxDistance=150"
    for filter in PCF2x2 PCF3x3 PCF5x5 PCF7x7; do
        "$penumbra" compare "$dir/$scene.gltf" --width 256 --height 144 --json --device "${PENUMBRA_DEVICE:-cpu}" \
            --set shadows.directional.filter=$filter $extra "$@" |
            python3 -c "import json,sys; m=json.load(sys.stdin); print('| $scene | $filter | %.3f | %.3f | %.4f |' % (m['misclassifiedPercent'], m['interiorMisclassifiedPercent'], m['meanAbsoluteError']))"
    done
done
