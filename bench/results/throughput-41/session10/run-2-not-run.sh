#!/bin/bash
# NOT RUN: no machine started in three attempts (two more were refused during lockouts), then too little device time was left to start one.
# Session 10, call 2: the final build (.gpu48/pt: shading traces its shadow rays up to 2^15
# triangles, each way of shading a program part of its own) against 54624b3 (.gpu47/pt), both as
# pt render runs by default, interleaved, 2 rounds, 1280x960, 64 spp, max depth 8; the bits; the
# first builds' lines. Carry .gpu45, .gpu47, .gpu48.
set -u
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
OLD=.gpu47/pt NEW=.gpu48/pt CMP=.gpu47/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'; }
for s in $SC; do
  n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr 2>&1 | grep -E "compiling|kernels [0-9.]+ s|finishing" | sed "s/^/$n: /" | cut -c1-160
  echo "bits $n: $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-100)"
done
echo "== warm $(el) s"
for r in 1 2; do for s in $SC; do
  n=$(basename $s .json)
  echo "$n round $r: old $($OLD render $s $R -o /tmp/q.exr 2>&1 | mp) final $($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)"
done; done
$NEW render tests/scenes/cornell $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"
echo "== done $(el) s"
