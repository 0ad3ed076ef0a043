#!/bin/sh
# SPDX-License-Identifier: MIT
# bench_build.sh [PT_A [PT_B]]: kernel build times per scene (feature set), cold (an empty kernel
# cache) and warm (the cache just filled), as pt reports them ("kernels N s"), for one or two pt
# builds interleaved (A, B, A, B per scene) so both see the same machine. A cold build is what a
# first render of a scene waits for: issue 39's goal is <= 10 s on the H200, <= 5 s on PoCL idle.
# Prints a table and writes OUT (default bench-build.csv): build,scene,features,cold_s,warm_s,
# cold_wall_s,warm_wall_s: the kernels line covers the parts built before the render starts; the
# difference of the whole runs' wall times (the wait column) also counts parts built later (the
# AOV pass's) and, on PoCL, the kernels it compiles at their first launch.
# Environment: DEVICE (default gpu if pt sees one, else cpu), SCENES (space-separated paths),
# PT_CL_OPTIONS etc. pass through.
set -eu
a=${1:-build/pt}; b=${2:-}
out=${OUT:-bench-build.csv}
dev=${DEVICE:-}
scenes=${SCENES:-"scenes/cornell-box scenes/bench-materials/materials.json scenes/bench-materials/env.json
tests/scenes/conductors tests/scenes/normalmap tests/scenes/textured tests/scenes/envmap
tests/scenes/glass tests/scenes/mix scenes/black-hole scenes/bench/dragon.json"}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
seconds() { # BIN SCENE CACHE -> "seconds wall features" of the kernels line and the whole run
    # (CUDA_CACHE_DISABLE: NVIDIA's driver keeps its own cache of compiled programs; cold means neither)
    t0=$(date +%s.%N)
    line=$(XDG_CACHE_HOME=$3 CUDA_CACHE_DISABLE=1 "$1" render "$2" ${dev:+--device $dev} --width 32 --height 24 --spp 1 \
        --max-depth 2 -o "$tmp/o.exr" 2>&1 |
        sed -n 's/.*kernels \([0-9.]*\) s ([^;]*; features: \([^)]*\)).*/\1 \2/p')
    t1=$(date +%s.%N)
    echo "${line%% *} $(awk "BEGIN { printf \"%.2f\", $t1 - $t0 }") ${line#* }"
}
echo "build,scene,features,cold_s,warm_s,cold_wall_s,warm_wall_s" >"$out"
i=0
for s in $scenes; do
    for side in A B; do
        if [ $side = A ]; then bin=$a; else bin=$b; fi
        [ -n "$bin" ] || continue
        i=$((i + 1)); cache=$tmp/cache$i
        cold=$(seconds "$bin" "$s" "$cache"); warm=$(seconds "$bin" "$s" "$cache")
        features=$(echo "$cold" | cut -d' ' -f3- | tr ',' ' ')
        echo "$side,$s,$features,$(echo "$cold" | cut -d' ' -f1),$(echo "$warm" | cut -d' ' -f1),$(echo "$cold" | cut -d' ' -f2),$(echo "$warm" | cut -d' ' -f2)" >>"$out"
    done
done
python3 - "$out" "$a" "$b" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(f"A = {sys.argv[2]}" + (f"\nB = {sys.argv[3]}" if sys.argv[3] else ""))
# wait: what a first run waits for the kernels (cold run - warm run): PoCL compiles each kernel
# when it is first launched, after the kernels line.
print(f"{'scene':42} {'side':>4} {'cold s':>8} {'warm s':>8} {'cold run':>9} {'warm run':>9} {'wait':>6}  features")
for r in rows:
    cold, warm = float(r['cold_wall_s']), float(r['warm_wall_s'])
    print(f"{r['scene']:42} {r['build']:>4} {r['cold_s']:>8} {r['warm_s']:>8} {cold:9.2f} "
          f"{warm:9.2f} {cold - warm:6.2f}  {r['features']}")
PY
