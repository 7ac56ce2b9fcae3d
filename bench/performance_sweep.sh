#!/usr/bin/env bash
# The measurements behind docs/performance.md, as one script (run on the GPU host, or here with
# PENUMBRA_DEVICE=cpu and smaller sizes). Writes one JSON per `penumbra bench` run into OUTDIR.
#   bench/performance_sweep.sh PENUMBRA OUTDIR [PRESET]
# PENUMBRA: the program (e.g. ".portable/bin/penumbra" with LD_LIBRARY_PATH=.portable/lib on a GPU host
# without packages: scripts/pack-portable.sh makes .portable/). PRESET:
#   gpu      1920x1080, field 1..400 engines with 16 spots, boxes 1k..1M, the 3000-frame orbit run
#   lavapipe 320x180, field 1..16, boxes 1k..100k (a 2-core CPU renders these in minutes)
#   raster   1920x1080: the GPU-driven shadow atlases: hw vs compute rasterizer per atlas against triangles
#            (field 1..400, 16 spots), cached vs uncached tiles with a still camera, objects 1k..1M
#   meshlets 1920x1080: meshlet culling on and off (visibility buffer, compute shadows)
# Every run uses one configuration: 4 cascades in a 4096² atlas, PCF5x5, soft cascade blend,
# spot/point shadows in a 4096² atlas (PCF5x5).
set -euo pipefail
penumbra=${1:?usage: performance_sweep.sh PENUMBRA OUTDIR [gpu|lavapipe]}
out=${2:?usage: performance_sweep.sh PENUMBRA OUTDIR [gpu|lavapipe]}
preset=${3:-gpu}
device=${PENUMBRA_DEVICE:-gpu}
model=()  # PENUMBRA_MODEL: the glTF gen:field copies, where assimp-testmodels is not installed
[ -n "${PENUMBRA_MODEL:-}" ] && model=(--model "$PENUMBRA_MODEL")
mkdir -p "$out"
config=(--set shadows.directional.atlasSize=4096 --set shadows.directional.cascadeCount=4
        --set shadows.directional.filter=PCF5x5 --set shadows.directional.cascadeBlend=soft
        --set shadows.spot.atlasSize=4096 --set shadows.spot.filter=PCF5x5)
if [ "$preset" = gpu ]; then
    size=(--width 1920 --height 1080); fields="1 4 16 25 64 100 200 400"; boxes="1000 10000 100000 1000000"
    frames=30; warmup=5
else
    size=(--width 320 --height 180); fields="1 4 16"; boxes="1000 10000 100000"; frames=8; warmup=2
fi
# The shadow distance that keeps a whole built-in scene shadowed (the default 100 m would leave the
# far part of large fields unshadowed): 2.5 x the side of its square, at least 100 m.
distance_for() {  # SCENE
    local kind=${1#gen:}; kind=${kind%%:*}; local count=${1#gen:*:}; count=${count%%:*}
    local spacing=3.0; [ "$kind" = boxes ] && spacing=1.2
    python3 -c "import math; print(max(100, math.ceil(2.5 * $spacing * math.ceil(math.sqrt($count)))))"
}
run() {  # NAME SCENE FRAMES [extra options]
    local name=$1 scene=$2 n=$3; shift 3
    set -- --set "shadows.maxDistance=$(distance_for "$scene")" "$@"
    echo "== $name: $scene, $n frames $*" >&2
    "$penumbra" bench "$scene" --device "$device" "${model[@]}" "${size[@]}" "${config[@]}" --frames "$n" --warmup "$warmup" \
        "$@" --json "$out/$name.json" > "$out/$name.txt"
    tail -n 4 "$out/$name.txt" >&2
}
if [ "$preset" = meshlets ]; then  # render.meshletCulling on and off, compute rasterizers
    size=(--width 1920 --height 1080); frames=30; warmup=5
    for m in true false; do
        for scene in gen:field:25:16 gen:field:100:16 gen:field:100:16:1008 gen:field:400:16; do
            name=$(echo "${scene#gen:}" | tr : _)
            run "${name}_meshlets_$m" "$scene" "$frames" --camera orbit --main-view visibility --raster compute \
                --set "render.meshletCulling=$m"
        done
    done
    exit 0
fi
if [ "$preset" = raster ]; then
    size=(--width 1920 --height 1080); frames=15; warmup=5
    for n in 1 4 16 25 64 100 200 400; do
        for r in hw compute; do run "field_${n}_16_$r" "gen:field:$n:16" "$frames" --camera orbit --raster "$r"; done
    done
    for c in true false; do
        run "field_100_16_static_cache_$c" gen:field:100:16 "$frames" --camera static --raster compute --set "shadows.cacheTiles=$c"
    done
    warmup=12; run field_100_16_auto gen:field:100:16 "$frames" --camera orbit; warmup=5
    for n in 1000 10000 100000 1000000; do run "boxes_${n}_compute" "gen:boxes:$n" 8 --camera orbit --raster compute; done
    exit 0
fi
for n in $fields; do run "field_${n}_16" "gen:field:$n:16" "$frames" --camera orbit; done
for n in $fields; do run "field_${n}_0" "gen:field:$n" "$frames" --camera orbit; done
for n in $boxes; do
    f=$frames; [ "$n" -ge 100000 ] && f=$((frames / 3 + 1))
    run "boxes_${n}" "gen:boxes:$n" "$f" --camera orbit
done
if [ "$preset" = gpu ]; then
    run field_25_16_long gen:field:25:16 3000 --camera orbit
    run field_100_16_static gen:field:100:16 "$frames" --camera static
fi
