#!/bin/bash
# Session 14, call D (call C never started; this is its short form for the device time left):
# this session's final build against session 13's on every scene, and against the issue's start
# at the issue's roulette on the Cornell box and the forest. 1280x960, 256 spp, max depth 8, best
# of 2 interleaved rounds. No Mitsuba: calls A and B measured it on the same kind of card, and
# their figures agree within 0.2%. Carry .gpu45 (libraries), .gpu59 (binaries: pt-final = 8657efc,
# pt-prev = 0f69a22, pt-start = 4774c8f, stripped; if .gpu59 is gone, rebuild them).
#   final  pt now (the any-hit visit without order, the pool up to 2^27 slots)
#   prev   session 13's final build (73e55e4's code)
#   start3 pt at 4774c8f (roulette from the third vertex); final3: final with -DPT_ROULETTE_DEPTH=3u
#   fused3, quant3 (the forest only): final3 with PT_CONNECT_IN_SHADING=1, PT_BVH_QUANTIZED=1
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
M="-cl-mad-enable -cl-no-signed-zeros"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
mkdir -p /tmp/g59 && tar xJf .gpu59/bins.tar.xz -C /tmp/g59
CMP=/tmp/g59/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
GAPS="tests/scenes/cornell /tmp/forest43"
runv() { local v=$1; shift; case $v in
  final) /tmp/g59/pt-final "$@";; prev) /tmp/g59/pt-prev "$@";; start3) /tmp/g59/pt-start "$@";;
  final3) PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" /tmp/g59/pt-final "$@";; esac; }
echo "== setup $(el) s"
for s in $SC; do n=$(basename $s .json)
  for v in final prev; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v-$v.txt 2>&1 || tail -2 /tmp/v-$v.txt; done
  echo "$n final: $(grep -o 'pool [0-9]* paths, [0-9]* windows' /tmp/v-final.txt); prev: $(grep -o 'pool [0-9]* paths, [0-9]* windows' /tmp/v-prev.txt)"
  echo "bits $n prev/final: $($CMP /tmp/prev-$n.exr /tmp/final-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-160)"
done
for s in $GAPS; do for v in start3 final3; do runv $v render $s $R -o /tmp/q.exr > /dev/null 2>&1; done; done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do
  for s in $SC; do n=$(basename $s .json)
    for v in final prev; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
  done
  for s in $GAPS; do n=$(basename $s .json)
    for v in start3 final3; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
  done
  echo "== round $r $(el) s"
done
python3 - $O/speed.csv <<'PY'
import csv, sys, collections
best = collections.defaultdict(float)
for r in csv.DictReader(open(sys.argv[1])):
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(s for s, v in best):
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}" for s, v in best if s == scene),
          f"final/prev={best[(scene, 'final')] / best[(scene, 'prev')]:.3f}")
PY
# The forest's gap at the third vertex: shading that traces its shadow rays (0.907 in session 10,
# before the any-hit visit and the larger pool) and quantised nodes, each against final3.
echo "scene,round,variant,mpaths,rays_per_path" > $O/forest.csv
for r in 1 2; do for v in final3 fused3 quant3; do
  [ $(el) -gt 300 ] && break 2
  case $v in final3) E="";; fused3) E="PT_CONNECT_IN_SHADING=1";; quant3) E="PT_BVH_QUANTIZED=1";; esac
  echo "forest43,$r,$v,$(env $E PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" /tmp/g59/pt-final render /tmp/forest43 $R -o /tmp/q.exr 2>&1 | mp)" >> $O/forest.csv
done; done
cat $O/forest.csv
echo "-- profile cornell final3" > $O/profiles.txt
runv final3 render tests/scenes/cornell $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%" >> $O/profiles.txt
echo "== done $(el) s"
