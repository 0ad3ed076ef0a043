#!/bin/bash
# Session 13's third call, which ran (started at its second attempt, with 249 s of device time
# left; run-2-not-run.sh never started): the room and the Cornell box, 65203ed against the final
# build (0b87606): the images' agreement (bench_compare_exr prints their means), two rounds of
# timings, and Mitsuba on both. Carry .gpu45, .gpu56, .whl.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > /tmp/pip.txt 2>&1; echo pip rc=$? >> /tmp/pip.txt) &
PIP=$!
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
mkdir -p /tmp/g56 && tar xJf .gpu56/bins.tar.xz -C /tmp/g56
BASE=/tmp/g56/pt-base NEW=/tmp/g56/pt-final CMP=/tmp/g56/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s.*/\1/p'; }
for s in /tmp/nw/normal-walls.json tests/scenes/cornell; do n=$(basename $s .json)
  $BASE render $s $R -o /tmp/base-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/final-$n.exr > /dev/null 2>&1
  echo "bits $n: $($CMP /tmp/base-$n.exr /tmp/final-$n.exr --tolerance 0 2>&1 | tail -1)"
  for r in 1 2; do echo "$n round $r: base $($BASE render $s $R -o /tmp/q.exr 2>&1 | mp) final $($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)"; done
done
echo "== pt $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for s in /tmp/nw/normal-walls.json tests/scenes/cornell; do
  python3 tools/bench_mitsuba.py $s --width 1280 --height 960 --spp 64 --max-depth 8 --reps 3 --variant cuda_ad_rgb --rr-depth 5 --csv $O/mitsuba.csv 2>&1 | grep -E "Mpaths|rror" | tail -3
done
echo "== done $(el) s"
