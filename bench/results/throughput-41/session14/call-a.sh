#!/bin/bash
# Session 14, call A: issue 41's table before and after in one call, at the issue's settings
# (1280x960, 256 spp, max depth 8, best of 2 interleaved rounds), with Mitsuba 3.9.1 cuda_ad_rgb
# at equal work; then experiments. Carry .gpu45 (libraries), .gpu58 (binaries), .whl (wheels).
#   start  pt at 4774c8f, the tree when the issue was filed (roulette from the third vertex)
#   rr3    pt now (73e55e4's code + the SPEC_ANY experiment behind its flag), roulette from the
#          third vertex (-DPT_ROULETTE_DEPTH=3u): the work per path, against start
#   final  pt now as users run it: roulette from the fifth vertex (issue 34), Mitsuba's default
# Mitsuba at rr_depth 3 (against start and rr3) and 5 (against final). Experiments, on the
# one-level scenes, each against final (every one should give final's bits):
#   anyt   -DPT_EXP_TIGHT_ANY: any hits without the closest hit's second cull and order
#   spec   -DPT_EXP_SPEC_ANY: any hits through the speculative walk (leaves postponed)
#   c05, c20  the 2-wide tree built with a triangle's SAH cost 0.5 and 2.0 (1.0: a node step)
# Each phase appends to its CSV under $OUT, so a call cut short keeps what it measured.
set -u
# bits and best: gpu-setup.sh (this call ran them as copies of the same text).
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g58 && tar xJf .gpu58/bins.tar.xz -C /tmp/g58
START=/tmp/g58/pt-start FINAL=/tmp/g58/pt-final CMP=/tmp/g58/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
SC1="tests/scenes/cornell /tmp/small-light.json tests/scenes/cornell-sphere /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors"
runv() { local v=$1; shift; case $v in
  start) $START "$@";; final) $FINAL "$@";;
  rr3) PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" $FINAL "$@";;
  anyt) PT_CL_OPTIONS="$M -DPT_EXP_TIGHT_ANY" $FINAL "$@";;
  spec) PT_CL_OPTIONS="$M -DPT_EXP_SPEC_ANY" $FINAL "$@";;
  c05) /tmp/g58/pt-c05 "$@";; c20) /tmp/g58/pt-c20 "$@";; esac; }
echo "== setup $(el) s"
# 1. Before and after: builds, then each image against its partner.
for s in $SC; do n=$(basename $s .json)
  for v in start rr3 final; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    grep -E "kernels [0-9.]+ s" /tmp/v.txt | sed "s/.*BVH/$n $v first: BVH/" | cut -c1-110; done
  echo "means $n start/rr3: $(bits /tmp/start-$n.exr /tmp/rr3-$n.exr)"
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  for v in start rr3 final; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
done; echo "== round $r $(el) s"; done
best $O/speed.csv start
# 2. Mitsuba at equal work: rr_depth 3 (the table) and 5 (pt's default now).
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for rr in 3 5; do for s in $SC; do
  [ $(el) -gt 420 ] && { echo "mitsuba: out of time at $s rr $rr"; break 2; }
  if [ $(basename $s) = forest43 ]; then MB="env MITSUBA_FLATTEN=1 python3 tools/mitsuba_forest.py"; else MB="python3 tools/bench_mitsuba.py"; fi
  $MB $s --width 1280 --height 960 --spp 256 --max-depth 8 --reps 2 --variant cuda_ad_rgb --rr-depth $rr --csv $O/mitsuba-rr$rr.csv 2>&1 | grep -E "Mpaths|rror" | tail -2
done; echo "== mitsuba rr $rr $(el) s"; done
# 3. Experiments against final, on the one-level scenes.
for s in $SC1; do n=$(basename $s .json)
  for v in anyt spec c05 c20; do
    [ $(el) -gt 500 ] && break 2
    runv $v render $s $R -o /tmp/$v-$n.exr > /dev/null 2>&1; echo "bits $n $v: $(bits /tmp/final-$n.exr /tmp/$v-$n.exr)"; done
done
echo "== experiments warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/experiments.csv
for r in 1 2; do for s in $SC1; do n=$(basename $s .json)
  [ $(el) -gt 560 ] && break 2
  for v in final anyt spec c05 c20; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/experiments.csv; done
done; echo "== experiments round $r $(el) s"; done
best $O/experiments.csv final
# 4. Where the Cornell box's time goes, at both roulettes.
for v in rr3 final; do echo "-- profile cornell $v"; runv $v render tests/scenes/cornell $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done > $O/profiles.txt 2>&1
echo "== done $(el) s"
