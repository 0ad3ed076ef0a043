#!/bin/sh
# SPDX-License-Identifier: MIT
# bench-ab.sh PT_A PT_B [SCENE_ARGS]...: two pt builds on the same scenes, interleaved (A, B, A,
# B, ...) so both see the same load and clocks, for before/after comparisons of a change. Each
# round runs `pt bench` once per build on every scene; the figure is the default mode's ("refill")
# Mpaths/s. Prints best and median per scene and build, and B/A of the bests; writes OUT.csv.
#   tools/bench-ab.sh old/bin/pt new/bin/pt            the default scene list below
# Environment: ROUNDS (default 5), SIZE (WxH, default 1280x960), SPP (16), DEPTH (8), DEVICE,
# SCENES (a space-separated list of scene paths), OUT (default bench-ab.csv).
set -eu
a=$1; b=$2
W=${SIZE:-1280x960}; w=${W%x*}; h=${W#*x}
spp=${SPP:-16}; depth=${DEPTH:-8}; rounds=${ROUNDS:-5}; out=${OUT:-bench-ab.csv}
scenes=${SCENES:-"scenes/cornell-box scenes/cornell-box/sphere.json scenes/cornell-box/mirror.json tests/scenes/textured"}
dev=${DEVICE:+--device $DEVICE}
echo "build,scene,round,mpaths_per_s" >"$out"
for r in $(seq "$rounds"); do
    for s in $scenes; do
        for side in A B; do
            if [ $side = A ]; then bin=$a; else bin=$b; fi
            m=$("$bin" bench "$s" $dev --width "$w" --height "$h" --spp "$spp" --max-depth "$depth" 2>/dev/null |
                awk '$1 == "refill" {print $3}')
            echo "$side,$s,$r,${m:-nan}" >>"$out"
        done
    done
done
python3 - "$out" "$a" "$b" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(f"A = {sys.argv[2]}\nB = {sys.argv[3]}")
print(f"{'scene':44} {'A best':>8} {'A med':>8} {'B best':>8} {'B med':>8} {'B/A':>6}  (Mpaths/s)")
for scene in dict.fromkeys(r["scene"] for r in rows):
    v = {s: [float(r["mpaths_per_s"]) for r in rows if r["scene"] == scene and r["build"] == s] for s in "AB"}
    ba = max(v["B"]) / max(v["A"]) if max(v["A"]) > 0 else float("nan")
    print(f"{scene:44} {max(v['A']):8.1f} {statistics.median(v['A']):8.1f} "
          f"{max(v['B']):8.1f} {statistics.median(v['B']):8.1f} {ba:6.3f}")
PY
