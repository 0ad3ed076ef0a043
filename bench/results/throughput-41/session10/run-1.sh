#!/bin/bash
# Session 10, call 1: the final build of session 9 (54624b3) on what session 9's call 2 was to
# measure and did not: the room's sorting alone (default vs --sort-materials, same maths), the
# stage profiles of the room, the room without its normal map and the Cornell box, the megakernel
# on the GPU (Cornell box, small light), and Mitsuba 3 on the other five scene types (one
# round, 1280x960, 64 spp, max depth 8). Carry .gpu45 (libs-small.tar.xz), .gpu47/pt, .whl.
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
mkdir -p /tmp/nw2 && cp /tmp/nw/* /tmp/nw2/ && python3 -c "
import json; p='/tmp/nw2/normal-walls.json'; s=json.load(open(p))
[m.pop('normal_map', None) for m in s['materials'].values()]; json.dump(s, open(p, 'w'))"
F=.gpu47/pt
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'; }
for s in tests/scenes/cornell /tmp/small-light.json; do $F render $s $R -o /tmp/q.exr > /dev/null 2>&1; done
echo "== setup $(el) s"
for r in 1 2 3; do
  for c in "" "--sort-materials"; do
    echo "room round $r ${c:-default}: $($F render /tmp/nw/normal-walls.json $R $c -o /tmp/q.exr 2>&1 | mp)"
  done
  echo "room-without-normal-map round $r: $($F render /tmp/nw2/normal-walls.json $R -o /tmp/q.exr 2>&1 | mp)"
  for s in tests/scenes/cornell /tmp/small-light.json; do
    echo "$(basename $s) round $r wavefront: $($F render $s $R -o /tmp/q.exr 2>&1 | mp)  megakernel: $(PT_MEGAKERNEL=1 $F render $s $R -o /tmp/q.exr 2>&1 | mp)  megakernel-packets-off: $(PT_MEGAKERNEL=1 PT_PACKETS=0 $F render $s $R -o /tmp/q.exr 2>&1 | mp)"
  done
done
echo "== rounds $(el) s"
for s in /tmp/nw/normal-walls.json /tmp/nw2/normal-walls.json tests/scenes/cornell /tmp/small-light.json; do echo "-- profile $s"
  $F render $s $R --profile -o /tmp/q.exr 2>&1 | grep -vE "^(loading|kernel|device|scene)" | head -40; done
echo "== profiles $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site PYTHON=python3 PT=$F DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1
timeout $(( 420 - $(el) )) tools/bench-vs-mitsuba.sh tests/scenes/cornell-sphere /tmp/small-light.json tests/scenes/envmap tests/scenes/conductors /tmp/torus-100k.json tests/scenes/cornell /tmp/nw/normal-walls.json -o $O/plain > $O/plain.txt 2>&1
echo "plain rc=$? $(el) s"; grep -A20 "renderer" $O/plain.txt || tail -30 $O/plain.txt
ls $O/plain 2>/dev/null | head
echo "== done $(el) s"
