#!/bin/sh
# SPDX-License-Identifier: MIT
# pt against Mitsuba 3 on this machine's CPU, interleaved so that both see the same load (shared
# machines drift by 20% from minute to minute): ROUNDS rounds of [Mitsuba llvm_ad_rgb, 3 timed
# renders; pt bench on PoCL], same scene, film, spp and max depth. Prints both, and writes
# OUT/mitsuba.csv and OUT/pt.csv.
#   tools/bench-vs-mitsuba.sh [SCENE] [OUT]     default scenes/cornell-box, bench/results/vs-mitsuba
# Environment: ROUNDS (default 4), WIDTH/HEIGHT (512), SPP (8), DEPTH (8), PT (build/pt).
set -eu
cd "$(dirname "$0")/.."
. tools/mitsuba-venv.sh
scene=${1:-scenes/cornell-box}
out=${2:-bench/results/vs-mitsuba}
PT=${PT:-build/pt}
W=${WIDTH:-512} H=${HEIGHT:-512} S=${SPP:-8} D=${DEPTH:-8}
mkdir -p "$out"
rm -f "$out/mitsuba.csv" "$out/pt.csv" "$out/pt_stages.csv" "$out/pt_live.csv"
for round in $(seq "${ROUNDS:-4}"); do
    echo "== round $round"
    "$VENV/bin/python" tools/bench_mitsuba.py "$scene" --width "$W" --height "$H" --spp "$S" \
        --max-depth "$D" --reps 3 --csv "$out/mitsuba.csv"
    "$PT" bench "$scene" --device cpu --width "$W" --height "$H" --spp "$S" --max-depth "$D" \
        --csv "$out/pt.csv" | grep -E '^(mode|refill) '
done
"$VENV/bin/python" - "$out" <<'PY'
import csv, statistics, sys
out = sys.argv[1]
mi = [float(r["mpaths_per_s"]) for r in csv.DictReader(open(f"{out}/mitsuba.csv"))]
pt = [float(r["mpaths_per_s"]) for r in csv.DictReader(open(f"{out}/pt.csv")) if r["mode"] == "refill"]
print(f"Mpaths/s   median  best   (runs)\nmitsuba    {statistics.median(mi):6.2f} {max(mi):6.2f}  ({len(mi)})\n"
      f"pt         {statistics.median(pt):6.2f} {max(pt):6.2f}  ({len(pt)})\n"
      f"pt/mitsuba {statistics.median(pt) / statistics.median(mi):6.2f} (medians)")
PY
