#!/bin/bash
# Session 9, call 1: the final build (flat BVHs for static instances within 2^20 baked triangles,
# NVIDIA's own division and square root, sorting where shading diverges) against the old
# behaviour, interleaved in one binary: --instancing always (two levels), PT_EXACT_MATHS=1 (the
# correctly rounded flag), --sort-materials on the room; then issue 41's table against Mitsuba.
# Carry .gpu45 (libs-small.tar.xz, bench_compare_exr), .gpu47/pt (make bundle's stripped pt), .whl.
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
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
python3 tools/make_forest.py --count 419 /tmp/forest420 >/dev/null 2>&1
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
F=.gpu47/pt
R="--device gpu --width 1280 --height 960"
echo "== setup $(el) s"
# Images and stages: flat against two levels.
for s in /tmp/forest43 /tmp/forest420; do
  $F render $s $R --spp 64 --max-depth 8 -o /tmp/flat.exr --profile 2> /tmp/flat.txt
  $F render $s $R --spp 64 --max-depth 8 --instancing always -o /tmp/two.exr --profile 2> /tmp/two.txt
  echo "$s flat vs two levels: $(.gpu45/bench_compare_exr /tmp/flat.exr /tmp/two.exr | head -1)" | tee -a $O/flat-images.txt
  for f in flat two; do echo "-- $s $f"; grep -E "BVH|Mpaths|intersect|shade|generate|compact|sort|features" /tmp/$f.txt; done >> $O/flat-profile.txt
done
echo "== images $(el) s"
SC=("/tmp/forest43 64 8" "/tmp/forest420 64 8" "tests/scenes/cornell 64 8" "/tmp/small-light.json 64 8" "/tmp/nw/normal-walls.json 64 8")
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2 3; do for s in "${SC[@]}"; do set -- $s
  for c in "old:PT_EXACT_MATHS=1" "new:PT_EXACT_MATHS=0"; do n=${c%%:*}; e=${c#*:}; x=""
    if [ $n = old ]; then case $1 in *forest*) x="--instancing always";; *normal-walls*) x="--sort-materials";; esac; fi
    m=$(env $e $F render $1 $R --spp $2 --max-depth $3 $x -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done
  case $1 in *forest*) m=$($F render $1 $R --spp $2 --max-depth $3 --instancing always -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'); echo "$r,two-level,$1,$2,$3,$m" >> $O/speed.csv;; esac
  done; echo "round $r $(el) s"; [ $(el) -gt 150 ] && break; done
python3 - $O/speed.csv <<'PY' | tee $O/speed-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['cfg'])].append(float(r['mpaths']))
for sc in sorted({k[:3] for k in d}):
    a,b=max(d.get(sc+("old",),[0])),max(d.get(sc+("new",),[0]))
    t=d.get(sc+("two-level",))
    extra=f"  two-level (new maths) {max(t):7.1f} ({b/max(t):.3f})" if t else ""
    print(f"{sc[0]:28s} {sc[1]:>3s}spp d{sc[2]:>2s} old {a:7.1f} new {b:7.1f} ({b/a if a else 0:.3f}){extra}")
PY
wait $PIP; cat $O/pip.txt
echo "== pip $(el) s"
export PYTHONPATH=/tmp/site PYTHON=python3 PT=$F DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1
MITSUBA_BENCH=tools/mitsuba_forest.py MITSUBA_FLATTEN=1 timeout $(( 360 - $(el) )) tools/bench-vs-mitsuba.sh /tmp/forest43 /tmp/forest420 -o $O/forest > $O/forest.txt 2>&1
echo "forest rc=$? $(el) s"; grep -A8 "renderer" $O/forest.txt || grep -E "cuda_ad_rgb:|^default" $O/forest.txt
timeout $(( 450 - $(el) )) tools/bench-vs-mitsuba.sh /tmp/nw/normal-walls.json tests/scenes/cornell -o $O/plain > $O/plain.txt 2>&1
echo "plain rc=$? $(el) s"; grep -A8 "renderer" $O/plain.txt || grep -E "cuda_ad_rgb:|^default" $O/plain.txt
echo "== done $(el) s"
