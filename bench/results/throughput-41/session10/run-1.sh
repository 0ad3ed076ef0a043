#!/bin/bash
# Session 10, call 1 (one call for what two were planned for; no machine had started yet):
# this session's build (.gpu47/pt-new: 8-bit linear textures stay 8-bit; shading that traces its
# own shadow rays behind PT_CONNECT_IN_SHADING=1) against session 9's final build (.gpu47/pt,
# 54624b3), interleaved, 2 rounds, 1280x960, 64 spp, max depth 8, with the images' bits; the
# room sorted and not; stage profiles; then Mitsuba 3 against pt bench (default and shade-connect
# rows) on the issue's scene types (one round). Carry .gpu45 (libs-small.tar.xz), .gpu47, .whl.
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
mkdir -p /tmp/nw2 && cp /tmp/nw/* /tmp/nw2/ && python3 -c "
import json; p='/tmp/nw2/normal-walls.json'; s=json.load(open(p))
[m.pop('normal_map', None) for m in s['materials'].values()]; json.dump(s, open(p, 'w'))"
OLD=.gpu47/pt NEW=.gpu47/pt-new CMP=.gpu47/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json /tmp/forest43 tests/scenes/envmap tests/scenes/conductors tests/scenes/cornell-sphere /tmp/torus-100k.json"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'; }
echo "== setup $(el) s"
# Warm the kernel caches (and the fused part) of both binaries; the bits.
for s in $SC; do
  n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr > /dev/null 2>&1
  PT_CONNECT_IN_SHADING=1 $NEW render $s $R -o /tmp/con-$n.exr > /dev/null 2>&1
  echo "bits $n: new/old $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-100)"
  echo "bits $n: connect/new $($CMP /tmp/new-$n.exr /tmp/con-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-100)"
done
echo "== warm $(el) s"
echo "scene,round,old,new,connect" > $O/speed.csv
for r in 1 2; do for s in $SC; do
  n=$(basename $s .json)
  a=$($OLD render $s $R -o /tmp/q.exr 2>&1 | mp)
  b=$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)
  c=$(PT_CONNECT_IN_SHADING=1 $NEW render $s $R -o /tmp/q.exr 2>&1 | mp)
  echo "$n,$r,$a,$b,$c" >> $O/speed.csv
done; done
python3 - $O/speed.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(f"{'scene':18s} {'old':>8s} {'new':>8s} {'connect':>8s} {'new/old':>8s} {'con/new':>8s}  (best of rounds, Mpaths/s)")
for n in dict.fromkeys(r['scene'] for r in rows):
    try:
        b = {k: max(float(r[k]) for r in rows if r['scene'] == n and r[k]) for k in ('old', 'new', 'connect')}
        print(f"{n:18s} {b['old']:8.1f} {b['new']:8.1f} {b['connect']:8.1f} {b['new']/b['old']:8.3f} {b['connect']/b['new']:8.3f}")
    except ValueError:
        print(n, 'missing values', [r for r in rows if r['scene'] == n])
PY
echo "== rounds $(el) s"
for r in 1; do for c in "" "--sort-materials"; do
  echo "room round $r ${c:-default}: $($NEW render /tmp/nw/normal-walls.json $R $c -o /tmp/q.exr 2>&1 | mp)  connect: $(PT_CONNECT_IN_SHADING=1 $NEW render /tmp/nw/normal-walls.json $R $c -o /tmp/q.exr 2>&1 | mp)"
done; done
for s in tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/nw2/normal-walls.json; do
  for e in 0 1; do echo "-- profile $s connect=$e"
    PT_CONNECT_IN_SHADING=$e $NEW render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done; done
echo "== profiles $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site PYTHON=python3 PT=$NEW DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1
timeout $(( 440 - $(el) )) tools/bench-vs-mitsuba.sh tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json tests/scenes/envmap tests/scenes/conductors tests/scenes/cornell-sphere /tmp/torus-100k.json -o $O/plain > $O/plain.txt 2>&1
echo "plain rc=$? $(el) s"; grep -A20 "renderer" $O/plain.txt || tail -30 $O/plain.txt
grep -h "shade-connect" $O/plain/pt.csv | cut -d, -f1-12 | head -10
echo "== done $(el) s"
