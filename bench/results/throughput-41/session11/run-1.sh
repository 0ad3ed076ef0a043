#!/bin/bash
# Session 11, call 1. Carry .gpu45 (libs-small.tar.xz), .gpu47 (54624b3's pt), .gpu49.
# A: the final build of session 10 (.gpu49/pt = 24ea678: shading traces its shadow rays up to
#    2^15 triangles, each way of shading a part of its own, texels scaled by a product) against
#    54624b3 (.gpu47/pt): first builds, bits, 2 interleaved rounds, 1280x960, 64 spp, depth 8.
# B: where the time goes, by marginal cost (.gpu49/pt-exp = 24ea678 + experiments.patch, every
#    experiment a -D flag through PT_CL_OPTIONS, same bits): the per-group ray counts skipped or
#    spread over 64 addresses, the extension walk / the shadow walk / one Sobol tuple done twice,
#    reverse_bits by brev; the independent sampler; work-group sizes 32 and 128.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
OLD=.gpu47/pt NEW=.gpu49/pt EXP=.gpu49/pt-exp CMP=.gpu49/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'; }
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json"
for s in $SC; do
  n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr 2>&1 | grep -E "kernels [0-9.]+ s|finishing|waiting" | sed "s/^/$n first: /" | cut -c1-160
  echo "bits $n: $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-110)"
done
echo "== A warm $(el) s"
echo "scene,round,old,final" > $O/final.csv
for r in 1 2; do for s in $SC; do
  n=$(basename $s .json)
  echo "$n,$r,$($OLD render $s $R -o /tmp/q.exr 2>&1 | mp),$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/final.csv
done; done
cat $O/final.csv
echo "== A done $(el) s"
M="-cl-mad-enable -cl-no-signed-zeros"
V="base NO_RAY_COUNTS SPREAD_COUNTS TWICE_TRACE TWICE_SHADOW TWICE_RNG BREV"
opt() { [ $1 = base ] && echo "$M" || echo "$M -DPT_EXP_$1=1"; }
SB="tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json"
for s in $SB; do n=$(basename $s .json)
  for v in $V; do
    PT_CL_OPTIONS="$(opt $v)" $EXP render $s $R -o /tmp/x-$n-$v.exr > /dev/null 2>&1
    echo "bits $n $v: $($CMP /tmp/new-$n.exr /tmp/x-$n-$v.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"
  done
done
echo "== B warm $(el) s"
echo "scene,round,variant,mpaths" > $O/exp.csv
for r in 1 2; do for s in $SB; do n=$(basename $s .json)
  for v in $V; do echo "$n,$r,$v,$(PT_CL_OPTIONS="$(opt $v)" $EXP render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/exp.csv; done
  echo "$n,$r,independent,$(PT_CL_OPTIONS="$M" $EXP render $s $R --sampler independent -o /tmp/q.exr 2>&1 | mp)" >> $O/exp.csv
  for l in 32 128; do echo "$n,$r,local$l,$(PT_LOCAL_SIZE=$l PT_CL_OPTIONS="$M" $EXP render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/exp.csv; done
done; echo "== B round $r $(el) s"; done
python3 - $O/exp.csv <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(r["scene"] for r in rows):
    base = best[(scene, "base")]
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / base:.3f})" for s, v in best if s == scene))
PY
for s in $SB; do n=$(basename $s .json)
  for v in $V; do echo "-- profile $n $v"; PT_CL_OPTIONS="$(opt $v)" $EXP render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== done $(el) s"
