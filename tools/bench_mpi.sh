#!/bin/sh
# SPDX-License-Identifier: MIT
# bench_mpi.sh [PT] [REPEATS]: MPI scaling on one machine: the same render on 1 then 2 ranks of
# `mpirun --bind-to core` (each rank pinned to one core, PoCL limited to one thread per rank:
# POCL_CPU_MAX_CU_NUM=1), through the unit path both times (--unit-spp 1), REPEATS times each.
# Writes bench/results/mpi-pocl/scaling-WxH-Nspp.csv (BENCH_MPI_WIDTH, _HEIGHT, _SPP: 320x240, 64): per run the render seconds rank 0 reports (loading
# and kernel builds excluded), the speed-up over the best 1-rank time, and what the other ranks'
# films cost rank 0 (messages, bytes, bytes per unit received, ms to receive and merge them), with
# the machine's load average and the job's wall and CPU seconds (user + system of every rank, by
# /usr/bin/time): on a machine that other work shares, the wall-clock speed-up depends on the
# share of the cores each job gets, while the CPU seconds of the same work show what the ranks
# themselves cost (cpu_ratio: the best 1-rank CPU seconds over this run's).
set -eu
pt=${1:-build/pt}
repeats=${2:-3}
width=${BENCH_MPI_WIDTH:-320}; height=${BENCH_MPI_HEIGHT:-240}; spp=${BENCH_MPI_SPP:-64}
out=bench/results/mpi-pocl
mkdir -p "$out"
csv=$out/scaling-${width}x${height}-${spp}spp.csv
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
echo "ranks,run,width,height,spp,units,render_s,mpaths_s,speedup,film_messages,film_bytes,bytes_per_unit,merge_ms,wall_s,cpu_s,cpu_ratio,loadavg_1min,cpu" >"$csv"
best1=""; cpu1=""
for ranks in 1 2; do
    for run in $(seq "$repeats"); do
        load=$(cut -d' ' -f1 /proc/loadavg)
        /usr/bin/time -f "%e %U %S" -o "$tmp/time" timeout 1200 mpirun --bind-to core --map-by core -n "$ranks" -x POCL_CPU_MAX_CU_NUM=1 \
            "$pt" render scenes/cornell-box --width "$width" --height "$height" --spp "$spp" \
            --unit-spp 1 -o "$tmp/out.exr" 2>"$tmp/err" >/dev/null
        seconds=$(sed -n 's/^pt: [0-9]* spp in \([0-9.]*\) s:.*/\1/p' "$tmp/err")
        mpaths=$(sed -n 's/^pt: [0-9]* spp in [0-9.]* s: \([0-9.]*\) Mpaths.*/\1/p' "$tmp/err")
        units=$(sed -n 's/^pt: \([0-9]*\) work units.*/\1/p' "$tmp/err")
        # "pt: films of N other ranks at rank 0: M messages, B bytes (P per unit), merged in T ms"
        films=$(sed -n 's/^pt: films of .*: \([0-9]*\) messages, \([0-9]*\) bytes (\([0-9]*\) per unit), merged in \([0-9.]*\) ms/\1,\2,\3,\4/p' "$tmp/err")
        [ -n "$films" ] || films="0,0,0,0"
        wall=$(cut -d' ' -f1 "$tmp/time")
        cpus=$(awk '{printf "%.2f", $2 + $3}' "$tmp/time")
        [ -n "$best1" ] || best1=$seconds
        [ -n "$cpu1" ] || cpu1=$cpus
        if [ "$ranks" = 1 ] && awk "BEGIN{exit !($seconds < $best1)}"; then best1=$seconds; fi
        if [ "$ranks" = 1 ] && awk "BEGIN{exit !($cpus < $cpu1)}"; then cpu1=$cpus; fi
        speedup=$(awk "BEGIN{printf \"%.3f\", $best1 / $seconds}")
        ratio=$(awk "BEGIN{printf \"%.3f\", $cpu1 / $cpus}")
        echo "$ranks,$run,$width,$height,$spp,$units,$seconds,$mpaths,$speedup,$films,$wall,$cpus,$ratio,$load,\"$cpu\"" | tee -a "$csv"
    done
done
echo "bench_mpi: $csv (speed-up: over the best 1-rank time)"
