#!/bin/bash
# NOT RUN: prepared this session; 6 attempts to start a machine failed and the device time ran out.
# Session 9, call 2: the final build against Mitsuba 3 on the other scene types (one
# round, 1280x960, 64 spp, max depth 8), and the room's sorting alone (default vs
# --sort-materials, same maths). Carry .gpu45 (libs-small.tar.xz), .gpu47/pt, .whl.
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
F=.gpu47/pt
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
for r in 1 2 3; do for c in "" "--sort-materials"; do
  echo "room round $r ${c:-default}: $($F render /tmp/nw/normal-walls.json $R $c -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')"
done; done
echo "== room $(el) s"
mkdir -p /tmp/nw2 && cp /tmp/nw/* /tmp/nw2/ && python3 -c "
import json; p='/tmp/nw2/normal-walls.json'; s=json.load(open(p))
[m.pop('normal_map', None) for m in s['materials'].values()]; json.dump(s, open(p, 'w'))"
for s in /tmp/nw/normal-walls.json /tmp/nw2/normal-walls.json tests/scenes/cornell; do echo "-- profile $s"
  $F render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%|live paths"; done
echo "== profiles $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site PYTHON=python3 PT=$F DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1
timeout $(( 400 - $(el) )) tools/bench-vs-mitsuba.sh tests/scenes/cornell-sphere /tmp/small-light.json tests/scenes/envmap tests/scenes/conductors /tmp/torus-100k.json -o /tmp/plain > /tmp/plain.txt 2>&1
echo "plain rc=$? $(el) s"; grep -A16 "renderer" /tmp/plain.txt || grep -E "cuda_ad_rgb:|^default" /tmp/plain.txt
echo "== done $(el) s"
