#!/bin/bash
# PoCL before and after for issue 41 (session 15, on the 2-core development machine): the start
# (4774c8f, the tree when the issue was filed, roulette from the third vertex) against now at the
# same roulette (now3) and as shipped (now5, the fifth vertex), 320x240, 32 spp, max depth 8,
# megakernel (PoCL's default), 5 interleaved rounds after a warm-up render of each.
#   START=path/to/pt-at-4774c8f NOW=build/pt bench/results/throughput-41/session15/pocl/pocl-ab.sh
# Writes pocl.csv beside this script. The small light and the forest: as gpu-setup.sh makes them.
cd "$(dirname "$0")/../../../../.." || exit 1
START=${START:?the start binary} NOW=${NOW:-build/pt}
OUTCSV=$(dirname "$0")/pocl.csv
R="--device cpu --width 320 --height 240 --spp 32 --max-depth 8"
MO="-cl-mad-enable -cl-no-signed-zeros -cl-fp32-correctly-rounded-divide-sqrt"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/forest43 tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s.*/\1/p'; }
runv() { local v=$1; shift; case $v in start) $START "$@";; now3) PT_CL_OPTIONS="$MO -DPT_ROULETTE_DEPTH=3u" $NOW "$@";; now5) $NOW "$@";; esac; }
echo "scene,round,variant,mpaths" > "$OUTCSV"
for s in $SC; do for v in start now3 now5; do runv $v render $s $R -o /tmp/pa-$v-$(basename $s .json).exr > /tmp/pa.txt 2>&1 || tail -3 /tmp/pa.txt; done; done
for r in 1 2 3 4 5; do for s in $SC; do for v in start now3 now5; do
  echo "$(basename $s .json),$r,$v,$(runv $v render $s $R -o /tmp/pq.exr 2>&1 | mp)" >> "$OUTCSV"
done; done; done
