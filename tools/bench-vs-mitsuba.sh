#!/bin/sh
# SPDX-License-Identifier: MIT
# pt against Mitsuba 3 on the same device kind, interleaved so that both see the same load (shared
# machines drift by 20% from minute to minute): ROUNDS rounds of [Mitsuba, 3 timed renders; pt bench],
# same scene, film, spp and max depth, for each scene given. Prints both, and writes
# OUT/mitsuba.csv and OUT/pt.csv (one row per render; the scene is a column).
#   tools/bench-vs-mitsuba.sh [SCENE...] [-o OUT]   default scenes/cornell-box, bench/results/vs-mitsuba
# Environment: DEVICE cpu (default: pt on PoCL, Mitsuba llvm_ad_rgb) or gpu (pt on the GPU's OpenCL,
# Mitsuba cuda_ad_rgb); VARIANT overrides the Mitsuba variant; ROUNDS (default 4), WIDTH/HEIGHT
# (512), SPP (8), DEPTH (8), RR_DEPTH (5: Mitsuba's rr_depth set to pt's Russian roulette, from the
# fifth vertex since 2026-12-06 (before, the third: RR_DEPTH=3 with such a pt), so that both trace
# the same rays per path), PT (build/pt), PYTHON (a python3 that imports
# mitsuba and numpy, e.g. from wheels installed with --target; default: .venv-mitsuba, created by
# tools/mitsuba-venv.sh), MITSUBA_BENCH (default tools/bench_mitsuba.py; tools/mitsuba_forest.py for scenes with transforms,
# instances and analytic lights: the forest and dragons of bench/README.md "Instancing").
# The material benchmark (bench/README.md "Materials"), on the GPU machine:
#   DEVICE=gpu WIDTH=1024 HEIGHT=1024 SPP=16 tools/bench-vs-mitsuba.sh \
#       scenes/bench-materials/materials.json scenes/bench-materials/env.json -o bench/results/vs-mitsuba-gpu
set -eu
cd "$(dirname "$0")/.."
if [ -n "${PYTHON:-}" ]; then VENV_PY=$PYTHON; else . tools/mitsuba-venv.sh; VENV_PY=$VENV/bin/python; fi
out=bench/results/vs-mitsuba
scenes=""
while [ $# -gt 0 ]; do
    case $1 in
        -o) out=$2; shift 2 ;;
        *) scenes="$scenes $1"; shift ;;
    esac
done
scenes=${scenes:-scenes/cornell-box}
PT=${PT:-build/pt}
DEVICE=${DEVICE:-cpu}
if [ "$DEVICE" = gpu ]; then VARIANT=${VARIANT:-cuda_ad_rgb}; else VARIANT=${VARIANT:-llvm_ad_rgb}; fi
W=${WIDTH:-512} H=${HEIGHT:-512} S=${SPP:-8} D=${DEPTH:-8}
mkdir -p "$out"
rm -f "$out/mitsuba.csv" "$out/pt.csv" "$out/pt_stages.csv" "$out/pt_live.csv"
for round in $(seq "${ROUNDS:-4}"); do
    for scene in $scenes; do
        echo "== round $round: $scene"
        "$VENV_PY" "${MITSUBA_BENCH:-tools/bench_mitsuba.py}" "$scene" --width "$W" --height "$H" --spp "$S" \
            --max-depth "$D" --reps 3 --variant "$VARIANT" --rr-depth "${RR_DEPTH:-5}" --csv "$out/mitsuba.csv"
        "$PT" bench "$scene" --device "$DEVICE" --width "$W" --height "$H" --spp "$S" --max-depth "$D" \
            --csv "$out/pt.csv" | grep -E '^(mode|default) '
    done
done
"$VENV_PY" - "$out" $scenes <<'PY'
import csv, os, statistics, sys
out, scenes = sys.argv[1], sys.argv[2:]
mi_rows = list(csv.DictReader(open(f"{out}/mitsuba.csv")))
# "default": what pt render does (material sorting chosen for the scene)
pt_rows = [r for r in csv.DictReader(open(f"{out}/pt.csv")) if r["mode"] == "default"]
print(f"{'scene':45s} {'renderer':10s} median   best  (runs)   Mpaths/s")
for scene in scenes:
    mi = [float(r["mpaths_per_s"]) for r in mi_rows if r["scene"] == scene]
    # pt bench names the scene as given, or its scene.json inside a folder (a prefix would also
    # take tests/scenes/cornell-sphere's rows for tests/scenes/cornell)
    given = os.path.normpath(scene)
    pt = [float(r["mpaths_per_s"]) for r in pt_rows
          if os.path.normpath(r.get("scene", scene)) in (given, os.path.join(given, "scene.json"))]
    if not pt:  # an older pt.csv without a recognisable scene column: one scene per run only
        pt = [float(r["mpaths_per_s"]) for r in pt_rows] if len(scenes) == 1 else []
    for name, v in (("mitsuba", mi), ("pt", pt)):
        if v:
            print(f"{scene:45s} {name:10s} {statistics.median(v):7.2f} {max(v):7.2f}  ({len(v)})")
    if mi and pt:
        print(f"{scene:45s} {'pt/mitsuba':10s} {statistics.median(pt) / statistics.median(mi):7.2f} (medians)")
PY
