#!/bin/bash
# Session 15, call C (prepared in session 14; ran on its third attempt): issue 41's table before
# and after in one call with session 14's final build, at the issue's settings (1280x960, 256 spp,
# max depth 8, best of 2 interleaved rounds), with Mitsuba 3.9.1 cuda_ad_rgb at equal work.
# Carry .gpu45 (libraries), .gpu59 (binaries), .whl (wheels). .gpu59 holds pt-final (8657efc,
# whose kernels d49d0c8 only refactors), pt-prev (0f69a22) and pt-start (4774c8f), stripped.
#   start  pt at 4774c8f, the tree when the issue was filed (roulette from the third vertex)
#   rr3    pt now (the any-hit visit without order, the pool up to 2^27 slots), roulette from the
#          third vertex (-DPT_ROULETTE_DEPTH=3u): the issue's work per path, against start
#   final  pt now as users run it: roulette from the fifth vertex (issue 34), Mitsuba's default
#   prev   session 13's final build (73e55e4's code), against final: this session's change
#   fused3, quant3, cap64, ls128 (the forest only, at the end): rr3 with PT_CONNECT_IN_SHADING=1,
#          PT_BVH_QUANTIZED=1, -cl-nv-maxrregcount=64 (+4% on the two-level forest in session 7)
#          or PT_LOCAL_SIZE=128
# Mitsuba at rr_depth 3 (against start and rr3) and 5 (against final). Each phase appends to its
# CSV under $OUT, so a call cut short keeps what it measured.
set -u
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g59 && tar xJf .gpu59/bins.tar.xz -C /tmp/g59
START=/tmp/g59/pt-start FINAL=/tmp/g59/pt-final PREV=/tmp/g59/pt-prev CMP=/tmp/g59/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
runv() { local v=$1; shift; case $v in
  start) $START "$@";; final) $FINAL "$@";; prev) $PREV "$@";;
  rr3) PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" $FINAL "$@";; esac; }
echo "== setup $(el) s"
# 1. Before and after: builds, then each image against its partner.
for s in $SC; do n=$(basename $s .json)
  for v in start rr3 final prev; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    grep -E "kernels [0-9.]+ s|pool [0-9]+" /tmp/v.txt | sed "s/.*BVH/$n $v first: BVH/; s/.*pool/$n $v: pool/" | cut -c1-110; done
  echo "means $n start/rr3: $(bits /tmp/start-$n.exr /tmp/rr3-$n.exr)"
  echo "bits $n prev/final: $(bits /tmp/prev-$n.exr /tmp/final-$n.exr)"
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  for v in start rr3 final prev; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
done; echo "== round $r $(el) s"; done
best $O/speed.csv start
# 2. Mitsuba at equal work: rr_depth 3 (the issue's table) and 5 (pt's default now).
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for rr in 3 5; do for s in $SC; do
  [ $(el) -gt 470 ] && { echo "mitsuba: out of time at $s rr $rr"; break 2; }
  if [ $(basename $s) = forest43 ]; then MB="env MITSUBA_FLATTEN=1 python3 tools/mitsuba_forest.py"; else MB="python3 tools/bench_mitsuba.py"; fi
  $MB $s --width 1280 --height 960 --spp 256 --max-depth 8 --reps 2 --variant cuda_ad_rgb --rr-depth $rr --csv $O/mitsuba-rr$rr.csv 2>&1 | grep -E "Mpaths|rror" | tail -2
done; echo "== mitsuba rr $rr $(el) s"; done
# The forest's gap at the third vertex: shading that traces its shadow rays (0.907 in session 10,
# before the any-hit visit and the larger pool) and quantised nodes, each against final3.
echo "scene,round,variant,mpaths,rays_per_path" > $O/forest.csv
for r in 1 2; do for v in final3 fused3 quant3 cap64 ls128; do
  [ $(el) -gt 540 ] && break 2
  X=""; case $v in final3) E="";; fused3) E="PT_CONNECT_IN_SHADING=1";; quant3) E="PT_BVH_QUANTIZED=1";;
    cap64) E=""; X="-cl-nv-maxrregcount=64";; ls128) E="PT_LOCAL_SIZE=128";; esac
  echo "forest43,$r,$v,$(env $E PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u $X" $FINAL render /tmp/forest43 $R -o /tmp/q.exr 2>&1 | mp)" >> $O/forest.csv
done; done
cat $O/forest.csv
best $O/forest.csv final3
# 3. Where the Cornell box's and the forest's time goes, at both roulettes.
for s in tests/scenes/cornell /tmp/forest43; do for v in rr3 final prev; do [ $(el) -gt 570 ] && break 2
  echo "-- profile $(basename $s) $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done; done > $O/profiles.txt 2>&1
echo "== done $(el) s"
