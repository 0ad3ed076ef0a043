#!/bin/bash
# NOT RUN (no device time left in session 12): the next call. Carry .gpu45, .gpu53, .gpu54 (or
# rebuild: pt-head = 26ebd38, pt-exp = pt-head + next-experiments.patch; .gpu53's pt-final =
# 23b713d, the build call 3 measured, before the review moved the speculative walk onto
# traversal_visit_children: `prev` checks that this costs nothing). .whl not needed.
# Experiments (every variant should give pt-head's bits):
#   tcall  -DPT_EXP_TEXTURE_CALL: one texture sampler that every lookup calls (noinline) instead
#          of a copy inlined at each (the room's shade_surface is 18,360 SASS instructions against
#          the Cornell box's 6,024, with about 42 inlined texel fetches);
#   core40, core32: -cl-nv-maxrregcount on the CORE part only (intersect_closest: 48 registers,
#          66% occupancy); conn64: on the CONNECT part only (shade_surface: 69-80 registers).
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
mkdir -p /tmp/g54 /tmp/g53 && tar xJf .gpu54/bins.tar.xz -C /tmp/g54 && tar xJf .gpu53/bins.tar.xz -C /tmp/g53
HEAD=/tmp/g54/pt-head EXP=/tmp/g54/pt-exp CMP=/tmp/g54/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
M="-cl-mad-enable -cl-no-signed-zeros"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
runv() { local v=$1; shift; case $v in
  head) $HEAD "$@";; exp) $EXP "$@";; prev) /tmp/g53/pt-final "$@";;
  tcall) PT_CL_OPTIONS="$M -DPT_EXP_TEXTURE_CALL" $EXP "$@";;
  core40) PT_EXP_MAXRREG_CORE=40 $EXP "$@";; core32) PT_EXP_MAXRREG_CORE=32 $EXP "$@";;
  conn64) PT_EXP_MAXRREG_CONNECT=64 $EXP "$@";;
  tcall64) PT_EXP_MAXRREG_CONNECT=64 PT_CL_OPTIONS="$M -DPT_EXP_TEXTURE_CALL" $EXP "$@";; esac; }
VS="prev exp tcall core40 core32 conn64 tcall64"
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors"
for s in $SC; do n=$(basename $s .json)
  $HEAD render $s $R -o /tmp/head-$n.exr > /dev/null 2>&1
  for v in $VS; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    echo "bits $n $v: $($CMP /tmp/head-$n.exr /tmp/$v-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"; done
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  for v in head $VS; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
done; echo "== round $r $(el) s"; done
python3 - $O/speed.csv <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(r["scene"] for r in rows):
    base = best[(scene, "head")]
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / base:.3f})" for s, v in best if s == scene))
PY
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do n=$(basename $s .json)
  for v in head tcall core40 conn64; do echo "-- profile $n $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== done $(el) s"
