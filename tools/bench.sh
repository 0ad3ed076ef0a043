#!/bin/sh
# SPDX-License-Identifier: MIT
# bench.sh [--device D] [--quick]: the wavefront benchmark suite (make bench). Runs `pt bench` on
# the suite's scenes (its ablations: refills, shadow queue, compaction, brute force on small
# scenes; per-stage times), on procedural tori of 10^3 .. 10^6 triangles, at several resolutions,
# and writes bench/results/<device>/wavefront.csv plus the full text output (wavefront.txt).
# PT=path/to/pt overrides the binary (default build/pt); PYTHON one with matplotlib for the plots. Scenes that need ../shared/assets are
# skipped when it is absent. --quick: fewer samples (for slow CPU devices).
set -eu
PT=${PT:-build/pt}
device=""; quick=0
while [ $# -gt 0 ]; do
    case $1 in
    --device) device=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    *) echo "usage: bench.sh [--device D] [--quick]" >&2; exit 2 ;;
    esac
done
dev_args=${device:+--device $device}
spp=16; [ $quick = 1 ] && spp=2

# The device's name names the results folder.
name=$($PT bench scenes/cornell-box --width 16 --height 16 --spp 1 $dev_args 2>/dev/null |
       sed -n 's/.*device \(.*\), pool.*/\1/p' | tr -c 'A-Za-z0-9._\n-' '-' | sed 's/--*/-/g; s/-$//')
[ -n "$name" ] || { echo "bench.sh: pt bench failed" >&2; exit 1; }
out=bench/results/$name
mkdir -p "$out"
csv=$out/wavefront.csv; txt=$out/wavefront.txt
rm -f "$csv" "$out/wavefront_stages.csv" "$out/wavefront_live.csv"
: >"$txt"

run() { # scene, then extra pt bench arguments
    echo "== $*" | tee -a "$txt"
    $PT bench "$@" $dev_args --csv "$csv" 2>>"$txt" | tee -a "$txt"
}

run scenes/cornell-box --width 1024 --height 1024 --spp $spp --max-depth 8
run scenes/cornell-box/sphere.json --width 1024 --height 1024 --spp $spp --max-depth 8
run tests/scenes/textured --width 1024 --height 1024 --spp $spp --max-depth 8
if [ -d ../shared/assets ]; then
    run scenes/bench/dragon.json --width 1024 --height 1024 --spp $spp --max-depth 8
    run scenes/bench/skull.json --width 1024 --height 1024 --spp $spp --max-depth 8
fi
# Triangle-count scaling, up to the 1M-triangle procedural scene (generated: too large to commit).
tori=${TMPDIR:-/tmp}/pt-bench-tori
[ -f "$tori/torus-1000000.json" ] || python3 tools/make_bench_scenes.py --tori "$tori" >/dev/null
for n in 1000 10000 100000 1000000; do
    run "$tori/torus-$n.json" --width 1024 --height 1024 --spp $spp --max-depth 8
done
# Resolution scaling on the classic box (4K exercises the sliced batches on small pools).
for size in 256x256 512x512 1024x1024 1920x1080 3840x2160; do
    run scenes/cornell-box --width ${size%x*} --height ${size#*x} --spp $spp --max-depth 8
done
echo "bench.sh: wrote $csv and $txt"
${PYTHON:-python3} tools/bench_plot.py "$out" || true
