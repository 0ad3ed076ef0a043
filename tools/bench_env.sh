#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench_env.sh: the environment map's benchmarks on one device, results under bench/results/<device>/
# (see bench/README.md, "Environment map"):
#   1. bench_env_variance: relMSE of NEE + MIS vs BSDF-only against a converged reference
#      (scenes/venice/sphere.json), env_variance.csv;
#   2. bench_env_build: host build of the sampling tables at 4k x 2k and 8k x 4k and a map's device
#      memory, env_build.csv;
#   3. an 8192 x 4096 map rendered by pt on the device (64 x 64, 4 spp): that it works, pt's scene
#      buffer size, the render time and the peak host memory, env_8k.txt.
# Usage: tools/bench_env.sh [--pt build/pt] [--tools build/tools] [--device gpu|cpu|P:D] [--quick]
# (--tools: where bench_env_variance and bench_env_build are; a bundle's bin/ holds them too)
# (--quick: smaller reference and fewer seeds, for PoCL). Build first: make build/pt tools.
set -euo pipefail
pt=build/pt tools=build/tools device= quick=
while [ $# -gt 0 ]; do
    case "$1" in
    --pt) pt=$2; shift 2 ;;
    --tools) tools=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    *) echo "bench_env.sh: unknown option $1" >&2; exit 1 ;;
    esac
done
device_args=()
[ -n "$device" ] && device_args=(--device "$device")
name=$("$pt" render scenes/venice/sphere.json --width 8 --height 8 --spp 1 "${device_args[@]}" -o /tmp/pt-bench-env-probe.png 2>&1 |
       sed -n 's/^pt: device \(.*\) (.*/\1/p' | head -1 | sed 's/[^A-Za-z0-9._]\+/-/g; s/-*$//')
out=bench/results/${name:-unknown-device}
mkdir -p "$out"
echo "results in $out"

refs=(--ref-spp 4096 --seeds 4)
[ -n "$quick" ] && refs=(--ref-spp 1024 --seeds 3)
"$tools"/bench_env_variance --pt "$pt" "${device_args[@]}" "${refs[@]}" --csv "$out/env_variance.csv"
"$tools"/bench_env_build --reps 3 --csv "$out/env_build.csv" --write-hdr /tmp/pt-bench-env-8k.hdr

dir=$(mktemp -d /tmp/pt-bench-env-XXXXXX)
trap 'rm -rf "$dir" /tmp/pt-bench-env-8k.hdr /tmp/pt-bench-env-probe.png' EXIT
cat >"$dir/scene.json" <<JSON
{"camera": {"eye": [0, 0.6, 4.5], "target": [0, -0.2, 0], "fov_y": 40},
 "objects": [{"obj": "$PWD/scenes/venice/sphere.obj"}],
 "environment": {"file": "/tmp/pt-bench-env-8k.hdr"}}
JSON
{
    echo "8192 x 4096 environment map, 64 x 64 at 4 spp:"
    if [ -x /usr/bin/time ]; then
        /usr/bin/time -f "peak host memory %M KiB, wall %e s (load + build + render)" \
            "$pt" render "$dir/scene.json" --width 64 --height 64 --spp 4 "${device_args[@]}" -o "$dir/8k.png" 2>&1
    else
        start=$(date +%s.%N)
        "$pt" render "$dir/scene.json" --width 64 --height 64 --spp 4 "${device_args[@]}" -o "$dir/8k.png" 2>&1
        echo "wall $(echo "$(date +%s.%N) - $start" | bc) s (load + build + render)"
    fi
} | tee "$out/env_8k.txt"
