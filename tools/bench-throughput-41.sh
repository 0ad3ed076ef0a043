#!/bin/sh
# SPDX-License-Identifier: MIT
# pt against Mitsuba 3 at equal work on every scene type of issue 41 (bench/README.md "GPU
# throughput"), in one run: the Cornell box, glass and mirror spheres, a small light, an env-map
# lit rough gold, rough metals, a 100k-triangle torus, a room of normal-mapped walls (6000
# triangles, make_bench_scenes.py --normal-walls), and a forest of 43
# instances (Mitsuba's copy flattened into one mesh per tree kind: its own instancing does not scale,
# bench/README.md "Instancing"). Each goes through tools/bench-vs-mitsuba.sh (interleaved rounds,
# Mitsuba's rr_depth at pt's Russian roulette), which prints the medians and writes the CSVs under
# OUT/plain and OUT/forest.
#   tools/bench-throughput-41.sh [OUT]   default bench/results/throughput-41/vs-mitsuba
# Environment as tools/bench-vs-mitsuba.sh (DEVICE, WIDTH, HEIGHT, SPP, DEPTH, ROUNDS, PT, PYTHON,
# VARIANT); the defaults here are the issue's: DEVICE=gpu, 1280x960, 256 spp, max depth 8, 2 rounds.
set -eu
cd "$(dirname "$0")/.."
out=${1:-bench/results/throughput-41/vs-mitsuba}
export DEVICE=${DEVICE:-gpu} WIDTH=${WIDTH:-1280} HEIGHT=${HEIGHT:-960} SPP=${SPP:-256} DEPTH=${DEPTH:-8}
export ROUNDS=${ROUNDS:-2}
gen=$(mktemp -d)
trap 'rm -rf "$gen"' EXIT
# The generated scenes (too large or too many files to commit): bench_efficiency.py's small light
# and torus, make_forest.py's forest.
python3 - "$gen" <<'PY'
import sys
sys.path.insert(0, "tools")
import bench_efficiency
bench_efficiency.small_light_scene(sys.argv[1])
bench_efficiency.torus_scene(sys.argv[1])
PY
python3 tools/make_forest.py --count 42 "$gen/forest43" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls "$gen/normal-walls" > /dev/null
python3 tools/make_material_scenes.py tests/scenes > /dev/null
tools/bench-vs-mitsuba.sh tests/scenes/cornell tests/scenes/cornell-sphere "$gen/small-light.json" \
    tests/scenes/envmap tests/scenes/conductors "$gen/torus-100k.json" \
    "$gen/normal-walls/normal-walls.json" \
    -o "$out/plain"
MITSUBA_BENCH=tools/mitsuba_forest.py MITSUBA_FLATTEN=1 tools/bench-vs-mitsuba.sh "$gen/forest43" \
    -o "$out/forest"
