#!/bin/sh
# SPDX-License-Identifier: MIT
# bench_multi_gpu.sh [-o OUT]: pt's unit scheduler on every GPU of the machine (issue 21). For each
# scene at 3840x2160, 256 spp, depth 8: one GPU (--device gpu through the unit path, --unit-spp 1)
# and all GPUs (--device all), Mpaths/s and per-device unit counts, and the number of pixel values
# that differ between the two images (bench_compare_exr: must be 0). Writes OUT/multi_gpu.csv and
# OUT/multi_gpu.txt (default bench/results/<gpu>-x<N>/). Run from the repository root or from a
# bundle (PT, COMPARE name the binaries; SCENES, WIDTH, HEIGHT, SPP, DEPTH override).
set -eu
PT=${PT:-build/pt}
COMPARE=${COMPARE:-build/tools/bench_compare_exr}
W=${WIDTH:-3840} H=${HEIGHT:-2160} S=${SPP:-256} D=${DEPTH:-8}
[ -d bench/forest-10k ] || python3 tools/make_forest.py --count 10000 >/dev/null
SCENES=${SCENES:-"scenes/cornell-box scenes/bench/dragon.json bench/forest-10k"}
gpus=$("$PT" devices | grep -cE '^ +[0-9]+:[0-9]+ .* GPU ' || true)
name=$(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1 | tr ' ' '-')
out=bench/results/${name:-gpu}-x$gpus
[ "${1:-}" = -o ] && out=$2
mkdir -p "$out"
csv=$out/multi_gpu.csv
echo "scene,devices,mpaths_per_s,seconds,device,units,device_mpaths_per_s,differing_values" >"$csv"
tmp=${TMPDIR:-/tmp}/pt-multi-gpu
mkdir -p "$tmp"
for scene in $SCENES; do
    for set in one all; do
        if [ $set = one ]; then dev="--device gpu --unit-spp 1"; else dev="--device all"; fi
        "$PT" render "$scene" $dev --width "$W" --height "$H" --spp "$S" --max-depth "$D" \
            -o "$tmp/$set.exr" >"$tmp/$set.log" 2>&1
        grep -E 'work units|device [0-9]+:[0-9]+ .*units|Mpaths/s' "$tmp/$set.log" | sed "s|^|$scene $set: |"
    done
    diff=$("$COMPARE" "$tmp/one.exr" "$tmp/all.exr" || true)
    echo "$scene: one vs all: $diff"
    ndiff=$(echo "$diff" | awk '{print $2}')
    for set in one all; do
        total=$(awk '/ spp in .*Mpaths/ {for (i = 1; i <= NF; i++) if ($i == "Mpaths/s,") print $(i-1)}' "$tmp/$set.log")
        secs=$(awk '/ spp in / {for (i = 1; i <= NF; i++) if ($i == "s:") print $(i-1)}' "$tmp/$set.log")
        n=$(grep -cE '^pt: device [0-9]+:[0-9]+ .*units in' "$tmp/$set.log" || true)
        grep -E '^pt: device [0-9]+:[0-9]+ .*units in' "$tmp/$set.log" |
            sed -E 's/^pt: device ([0-9]+:[0-9]+) .*: ([0-9]+) units in [0-9]+ runs, ([0-9.]+) Mpaths.*/\1 \2 \3/' |
            while read -r d u m; do
                echo "$scene,$n,$total,$secs,$d,$u,$m,$ndiff" >>"$csv"
            done
    done
done | tee "$out/multi_gpu.txt"
echo "wrote $csv"
