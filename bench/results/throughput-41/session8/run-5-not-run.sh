#!/bin/bash
# NOT RUN: prepared for the final build, refused because the session's device time was spent.
# Carry .gpu45 (libs-small.tar.xz), .gpu46/pt-final (make bundle's stripped pt) and .whl.
# Session 8, call 5: the final build: its default (NVIDIA's own division and square root; sorting
# only where shading diverges) against the old behaviour (PT_EXACT_MATHS=1, and --sort-materials
# on the normal-mapped room, which the old rule sorted) interleaved, then issue 41's table.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee $O/gpu.txt
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1; echo pip rc=$? >> $O/pip.txt) &
PIP=$!
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
[ -d /tmp/forest43 ] || python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
F=.gpu46/pt-final
echo "== setup $(el) s"
SC=("tests/scenes/cornell 64 8" "tests/scenes/cornell-sphere 64 8" "/tmp/small-light.json 64 8" "tests/scenes/envmap 64 8" "tests/scenes/conductors 64 8" "/tmp/torus-100k.json 64 8" "/tmp/nw/normal-walls.json 64 8 --sort-materials" "/tmp/forest43 64 8")
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2; do for s in "${SC[@]}"; do set -- $s
  for c in "exact:PT_EXACT_MATHS=1" "default:PT_EXACT_MATHS=0"; do n=${c%%:*}; e=${c#*:}; x=""; [ $n = exact ] && x="${4:-}"
    m=$(env $e $F render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 $x -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done; done; echo "round $r $(el) s"; [ $(el) -gt 80 ] && break; done
python3 - $O/speed.csv <<'PY' | tee $O/speed-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['cfg'])].append(float(r['mpaths']))
for sc in sorted({k[:3] for k in d}):
    a,b=max(d.get(sc+("exact",),[0])),max(d.get(sc+("default",),[0]))
    print(f"{sc[0]:30s} {sc[1]:>3s}spp d{sc[2]:>2s} exact {a:7.1f} default {b:7.1f} ({b/a if a else 0:.3f})")
PY
wait $PIP; cat $O/pip.txt
export PYTHONPATH=/tmp/site PYTHON=python3 PT=$F DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1
timeout $(( 200 - $(el) )) tools/bench-vs-mitsuba.sh /tmp/nw/normal-walls.json -o $O/nw 2>&1 | grep -A3 renderer
MITSUBA_BENCH=tools/mitsuba_forest.py MITSUBA_FLATTEN=1 timeout $(( 240 - $(el) )) tools/bench-vs-mitsuba.sh /tmp/forest43 -o $O/forest 2>&1 | grep -A3 renderer
echo "== done $(el) s"
