#!/bin/bash
# Session 14, call B: the two candidates call A left, on every scene, and the two gaps
# (the Cornell box's 2 G paths/s and the forest's 3x, at the roulette) with Mitsuba in the
# same call. 1280x960, 256 spp, max depth 8, best of 2 interleaved rounds. Carry .gpu45, .gpu58,
# .whl (as call A).
#   final  pt now (dd0ee92's code), roulette from the fifth vertex
#   anyt   -DPT_EXP_TIGHT_ANY (call A: 0.98-1.03 on six scenes)
#   p26    PT_POOL_SIZE=2^26 (the default is 2^25 on an H100, from an eighth of its memory)
#   both   anyt and p26;  p27: both with 2^27 slots (a few scenes)
#   *3     the same with roulette from the third vertex (-DPT_ROULETTE_DEPTH=3u); start3: 4774c8f
set -u
# bits and best: gpu-setup.sh (this call ran them as copies of the same text).
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g58 && tar xJf .gpu58/bins.tar.xz -C /tmp/g58
START=/tmp/g58/pt-start FINAL=/tmp/g58/pt-final CMP=/tmp/g58/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
GAPS="tests/scenes/cornell /tmp/forest43"
A="-DPT_EXP_TIGHT_ANY" D3="-DPT_ROULETTE_DEPTH=3u"
runv() { local v=$1; shift; case $v in
  final) $FINAL "$@";;
  anyt) PT_CL_OPTIONS="$M $A" $FINAL "$@";;
  p26) PT_POOL_SIZE=67108864 $FINAL "$@";;
  both) PT_POOL_SIZE=67108864 PT_CL_OPTIONS="$M $A" $FINAL "$@";;
  p27) PT_POOL_SIZE=134217728 PT_CL_OPTIONS="$M $A" $FINAL "$@";;
  start3) $START "$@";;
  final3) PT_CL_OPTIONS="$M $D3" $FINAL "$@";;
  both3) PT_POOL_SIZE=67108864 PT_CL_OPTIONS="$M $A $D3" $FINAL "$@";;
  p273) PT_POOL_SIZE=134217728 PT_CL_OPTIONS="$M $A $D3" $FINAL "$@";; esac; }
vs() { case $(basename $1 .json) in cornell|small-light|forest43) echo "final anyt p26 both p27";; *) echo "final anyt p26 both";; esac; }
echo "== setup $(el) s"
for s in $SC; do n=$(basename $s .json)
  for v in $(vs $s); do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    [ $v = final ] || echo "bits $n $v: $(bits /tmp/final-$n.exr /tmp/$v-$n.exr)"; done
done
for s in $GAPS; do n=$(basename $s .json)
  for v in start3 final3 both3 p273; do runv $v render $s $R -o /tmp/$v-$n.exr > /dev/null 2>&1; done
  echo "bits $n both3: $(bits /tmp/final3-$n.exr /tmp/both3-$n.exr)"
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do
  for s in $SC; do n=$(basename $s .json)
    for v in $(vs $s); do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
  done
  for s in $GAPS; do n=$(basename $s .json)
    for v in start3 final3 both3 p273; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
  done
  echo "== round $r $(el) s"
done
best $O/speed.csv final
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for rr in 3 5; do for s in $GAPS; do
  if [ $(basename $s) = forest43 ]; then MB="env MITSUBA_FLATTEN=1 python3 tools/mitsuba_forest.py"; else MB="python3 tools/bench_mitsuba.py"; fi
  $MB $s --width 1280 --height 960 --spp 256 --max-depth 8 --reps 2 --variant cuda_ad_rgb --rr-depth $rr --csv $O/mitsuba-rr$rr.csv 2>&1 | grep -E "Mpaths|rror" | tail -2
done; done
echo "== mitsuba $(el) s"
for s in $GAPS; do n=$(basename $s .json); for v in final both final3 both3; do
  [ $(el) -gt 540 ] && break 2
  echo "-- profile $n $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"
done; done > $O/profiles.txt 2>&1
echo "== done $(el) s"
