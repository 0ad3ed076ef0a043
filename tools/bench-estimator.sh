#!/bin/sh
# SPDX-License-Identifier: MIT
# bench-estimator.sh: pt's estimator choices measured against the Mitsuba references of
# tests/references (bench/README.md "Sampler and estimator"): for each scene and variant, SEEDS
# renders at the reference's size and SPP samples; relMSE (tools/bench_relmse.c) and pt's own
# render time; prints mean relMSE, time and efficiency 1 / (relMSE x seconds) per scene and
# variant, and writes OUT (CSV, one row per render). Variants are "NAME|PT_CL_OPTIONS extra|pt
# arguments"; the roulette depth is a build option (PT_ROULETTE_DEPTH, shade_surface.cl).
#   tools/bench-estimator.sh                     the default scenes and variants below
# Environment: SCENES, SPP (64), SEEDS (4), PT (build/pt), OUT (bench-estimator.csv), VARIANTS
# (newline-separated), MATHS (the maths options PT_CL_OPTIONS replaces; default pt's on PoCL).
set -eu
cd "$(dirname "$0")/.."
PT=${PT:-build/pt}
spp=${SPP:-64}; seeds=${SEEDS:-4}; out=${OUT:-bench-estimator.csv}
maths=${MATHS:-"-cl-mad-enable -cl-no-signed-zeros -cl-fp32-correctly-rounded-divide-sqrt"}
scenes=${SCENES:-"cornell cornell-sphere conductors envmap envmap-diffuse glass"}
variants=${VARIANTS:-"sobol rr3||--sampler sobol
independent rr3||--sampler independent
sobol rr5|-DPT_ROULETTE_DEPTH=5u|--sampler sobol
independent rr5|-DPT_ROULETTE_DEPTH=5u|--sampler independent"}
[ -x build/tools/bench_relmse ] || make build/tools/bench_relmse >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "scene,variant,seed,spp,seconds,relmse" >"$out"
for scene in $scenes; do
    ref=tests/references/$scene.exr
    echo "$variants" | while IFS='|' read -r name defines args; do
        # warm-up (seed 0, not counted): PoCL compiles the kernels at their first launch, inside
        # the render time pt reports
        # shellcheck disable=SC2086
        PT_CL_OPTIONS="$maths $defines" "$PT" render "tests/scenes/$scene/scene.json" $args --spp 1 \
            -o "$tmp/img.exr" 2>/dev/null >&2 || true
        for s in $(seq "$seeds"); do
            # shellcheck disable=SC2086 # args are words
            secs=$(PT_CL_OPTIONS="$maths $defines" "$PT" render "tests/scenes/$scene/scene.json" $args \
                --spp "$spp" --seed "$s" -o "$tmp/img.exr" 2>&1 | sed -n 's/.* spp in \([0-9.]*\) s.*/\1/p')
            rel=$(build/tools/bench_relmse "$ref" "$tmp/img.exr" | awk '{print $3}')
            echo "$scene,$name,$s,$spp,$secs,$rel" >>"$out"
        done
    done
done
awk -F, 'NR > 1 {k = $1 "," $2; n[k]++; t[k] += $5; e[k] += $6; if (!(k in o)) {o[k] = ++m; key[m] = k}}
    END {printf "%-16s %-18s %10s %9s %12s\n", "scene", "variant", "relMSE", "seconds", "efficiency";
         for (i = 1; i <= m; i++) {k = key[i]; split(k, p, ",");
             printf "%-16s %-18s %10.4g %9.3f %12.4g\n", p[1], p[2], e[k] / n[k], t[k] / n[k],
                    1 / ((e[k] / n[k]) * (t[k] / n[k]))}}' "$out"
