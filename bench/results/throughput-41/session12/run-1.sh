#!/bin/bash
# Session 12, call 1. Carry .gpu45 (libs-small.tar.xz), .gpu51, .whl (Mitsuba 3.9.1 wheels).
# .gpu51/bins.tar.xz: pt-final = 24ea678 (session 10's final build); pt-new = 28c627e (session 11's: brev,
# all-slots launches off by default); pt-exp = pt-new + experiments.patch (PT_EXP_TRI_COST
# overrides the 2-wide SAH triangle cost; 1 = default); pt-spec = pt-exp + the speculative walk
# (experiments2.patch: -DPT_EXP_SPECULATIVE=1 votes, 2 while-while).
# 1. bits and first builds on 8 scenes; 2. two interleaved rounds of final/new on 8 scenes and
# of variants on 4 (all-slots launches, 4-wide BVH, register caps, SAH triangle costs);
# 3. ptxas -v and SASS of the kernel cache's PTX; 4. Mitsuba 3 cuda_ad_rgb on 7 scenes.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > /tmp/pip.txt 2>&1; echo pip rc=$? >> /tmp/pip.txt) &
PIP=$!
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
mkdir -p /tmp/g51 && tar xJf .gpu51/bins.tar.xz -C /tmp/g51
OLD=/tmp/g51/pt-final NEW=/tmp/g51/pt-new EXP=/tmp/g51/pt-exp SPEC=/tmp/g51/pt-spec CMP=/tmp/g51/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
M="-cl-mad-enable -cl-no-signed-zeros"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors"
SB="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere"
for s in $SC; do n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr 2>&1 | grep -E "kernels [0-9.]+ s" | sed "s/.*BVH/$n first: BVH/" | cut -c1-120
  echo "bits $n new/final: $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"
done
# variant name -> environment
var() { case $1 in
  new) echo "";; all0) echo "PT_ALL_SLOTS_PERCENT=0";; all75) echo "PT_ALL_SLOTS_PERCENT=75";;
  w4) echo "PT_BVH_WIDTH=4";; rr64) echo "PT_CL_OPTIONS=-cl-mad-enable#-cl-no-signed-zeros#-cl-nv-maxrregcount=64";;
  rr40) echo "PT_CL_OPTIONS=-cl-mad-enable#-cl-no-signed-zeros#-cl-nv-maxrregcount=40";;
  tc05) echo "PT_EXP_TRI_COST=0.5";; tc2) echo "PT_EXP_TRI_COST=2";;
  spec1) echo "PT_CL_OPTIONS=-cl-mad-enable#-cl-no-signed-zeros#-DPT_EXP_SPECULATIVE=1";;
  spec2) echo "PT_CL_OPTIONS=-cl-mad-enable#-cl-no-signed-zeros#-DPT_EXP_SPECULATIVE=2";; esac; }
runv() { local v=$1; shift; local e b=$EXP; e=$(var $v); case $v in spec*) b=$SPEC;; esac
  if [ -n "$e" ]; then env "${e//#/ }" $b "$@"; else $b "$@"; fi; }
VS="new all0 w4 rr64 tc05 tc2 spec1 spec2"
for s in $SB; do n=$(basename $s .json)
  for v in $VS; do runv $v render $s $R -o /tmp/v-$n-$v.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    echo "bits $n $v/new: $($CMP /tmp/new-$n.exr /tmp/v-$n-$v.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"; done
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  echo "$n,$r,final,$($OLD render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
  echo "$n,$r,new,$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
  case " $SB " in *" $s "*) for v in $VS; do [ $v = new ] && continue
    echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done;; esac
done; echo "== round $r $(el) s"; done
python3 - $O/speed.csv <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(r["scene"] for r in rows):
    base = best[(scene, "final")]
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / base:.3f})" for s, v in best if s == scene))
PY
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do n=$(basename $s .json)
  for v in new w4 spec1; do echo "-- profile $n $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== profiles $(el) s"
export PATH=$PATH:/usr/local/cuda/bin
mkdir -p /tmp/sass
python3 - > $O/ptxas.txt 2>&1 <<'PY'
import glob, os, subprocess
for n, path in enumerate(sorted(p for p in glob.glob('/tmp/ptcache/**', recursive=True) if os.path.isfile(p))):
    data = open(path, 'rb').read()
    i = data.find(b'//')
    if i < 0 or b'.entry' not in data:
        continue
    base = f'/tmp/sass/p{n:02d}'
    open(base + '.ptx', 'wb').write(data[i:])
    kernels = [l.split()[-1].split('(')[0] for l in data[i:].decode(errors='replace').splitlines() if '.entry' in l]
    print('==', path, len(data), ' '.join(kernels))
    r = subprocess.run(['ptxas', '-arch=sm_90', '-v', '-o', base + '.cubin', base + '.ptx'], capture_output=True, text=True)
    print(r.stderr[-6000:])
    s = subprocess.run(['cuobjdump', '-sass', base + '.cubin'], capture_output=True, text=True)
    open(base + '.sass', 'w').write(s.stdout)
PY
tar cJf $O/sass.tar.xz -C /tmp/sass . 2>/dev/null; ls -la $O
echo "== sass $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for s in tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json tests/scenes/cornell-sphere /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors; do
  [ $(el) -gt 500 ] && { echo "mitsuba: out of time at $s"; break; }
  python3 tools/bench_mitsuba.py $s --width 1280 --height 960 --spp 64 --max-depth 8 --reps 3 --variant cuda_ad_rgb --rr-depth 5 --csv $O/mitsuba.csv 2>&1 | grep -E "Mpaths|rror" | tail -3
done
echo "== done $(el) s"
