#!/bin/bash
# Session 8, call 3 (call 2 + call 1 in one): spatial splits (PT_BVH_SPATIAL) and the shadow queue without the waits clear
# (PT_EXP_CLEAR_ALWAYS restores it), against HEAD (8fe096f): same bits, interleaved speed.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee $O/gpu.txt
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
[ -d /tmp/forest43 ] || python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
H=.gpu45/pt-head N=.gpu46/pt-new
echo "== setup $(el) s"
SC=("/tmp/small-light.json 64 64" "tests/scenes/cornell 64 64" "scenes/cornell-box 64 8" "tests/scenes/envmap 64 64" "tests/scenes/conductors 64 64" "/tmp/torus-100k.json 64 64" "/tmp/torus.obj 64 8" "/tmp/forest43 16 8")
for s in "${SC[@]}"; do set -- $s
  $H render $1 --device gpu --width 1280 --height 960 --spp 16 --max-depth $3 -o /tmp/b-h.exr > /dev/null 2>&1
  $N render $1 --device gpu --width 1280 --height 960 --spp 16 --max-depth $3 -o /tmp/b-n.exr 2> /tmp/b-n.txt
  PT_BVH_SPATIAL=0 $N render $1 --device gpu --width 1280 --height 960 --spp 16 --max-depth $3 -o /tmp/b-o.exr 2> /tmp/b-o.txt
  echo "$1 new/head: $(.gpu45/bench_compare_exr /tmp/b-n.exr /tmp/b-h.exr | head -1) | BVH new $(grep -o 'BVH [0-9.]* s' /tmp/b-n.txt) objects $(grep -o 'BVH [0-9.]* s' /tmp/b-o.txt)" | tee -a $O/bits.txt
done
echo "== bits $(el) s"
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2; do for s in "${SC[@]}"; do set -- $s
  for c in "head" "new" "objects:PT_BVH_SPATIAL=0" "clear:PT_CL_OPTIONS=-DPT_EXP_CLEAR_ALWAYS"; do n=${c%%:*}; e=${c#*:}; [ "$e" = "$c" ] && e=""
    B=$N; [ $n = head ] && B=$H
    m=$(env $e $B render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done; done; echo "round $r $(el) s"; [ $(el) -gt 250 ] && break; done
python3 - $O/speed.csv <<'PY' | tee $O/speed-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['cfg'])].append(float(r['mpaths']))
cf=["head","new","objects","clear"]
for sc in sorted({k[:3] for k in d}):
    base=max(d.get(sc+("head",),[0])) or 1
    print(f"{sc[0]:30s} {sc[1]:>3s}spp d{sc[2]:>2s} " + " ".join(f"{c} {max(d.get(sc+(c,),[0])):7.1f}({max(d.get(sc+(c,),[0]))/base:.3f})" for c in cf))
PY
echo "== ab $(el) s"
python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1; echo pip rc=$? >> $O/pip.txt
echo "== pip $(el) s"
PYTHONPATH=/tmp/site PYTHON=python3 PT=$H SPP=64 ROUNDS=1 timeout $(( 575 - $(el) )) tools/bench-throughput-41.sh $O/t41 > $O/t41.txt 2>&1
echo "t41 rc=$? $(el) s"
grep -A30 "renderer" $O/t41.txt
for f in $O/t41/plain/mitsuba.csv $O/t41/plain/pt.csv $O/t41/forest/mitsuba.csv $O/t41/forest/pt.csv; do [ -f $f ] && python3 - $f <<'PY'
import csv,sys
rows=list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    if r.get('mode','default') in ('default',): print(sys.argv[1].split('/')[-2], sys.argv[1].split('/')[-1], r.get('scene'), r.get('mpaths_per_s'))
PY
done
echo "== done $(el) s"
