#!/bin/bash
# Session 7, call C: the new default pool (2^25 on GPUs within 1/8 of the memory) against the old
# (2^21 x 16): same bits, long renders, frames, wall time with allocation, error per second.
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
[ -d /tmp/forest ] || python3 tools/make_forest.py --count 1000 /tmp/forest >/dev/null 2>&1
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1; echo pip rc=$? >> $O/pip.txt) &
PIP=$!
N=.gpu45/pt-new
OLD="PT_POOL_SIZE=2097152 PT_WINDOW_POOLS=16"
echo "== setup $(el) s"
for s in /tmp/small-light.json tests/scenes/cornell scenes/cornell-box tests/scenes/envmap tests/scenes/conductors /tmp/torus-100k.json /tmp/forest; do
  env $OLD $N render $s --device gpu --width 1280 --height 960 --spp 64 --max-depth 64 -o /tmp/b-old.exr > /dev/null 2>&1
  $N render $s --device gpu --width 1280 --height 960 --spp 64 --max-depth 64 -o /tmp/b-new.exr 2> /tmp/b-new.txt
  echo "$s new/old: $(.gpu45/bench_compare_exr /tmp/b-new.exr /tmp/b-old.exr | head -1) | $(grep -o 'pool.*' /tmp/b-new.txt)" | tee -a $O/bits.txt
done
echo "== bits $(el) s"
echo "round,cfg,scene,spp,depth,w,h,mpaths" > $O/frames.csv
SC=("/tmp/small-light.json 64 64 1280 960" "tests/scenes/cornell 64 64 1280 960" "scenes/cornell-box 16 8 1280 960" "tests/scenes/envmap 64 64 1280 960" "tests/scenes/conductors 64 64 1280 960" "/tmp/torus-100k.json 64 64 1280 960" "/tmp/forest 16 8 1280 960" "scenes/cornell-box 64 8 3840 2160"
    "scenes/cornell-box 1024 8 1280 960" "/tmp/small-light.json 512 64 1280 960" "tests/scenes/envmap 256 64 1280 960" "/tmp/torus-100k.json 128 64 1280 960")
for r in 1 2 3; do for s in "${SC[@]}"; do set -- $s
  for c in "old:$OLD" "p24x4:PT_POOL_SIZE=16777216 PT_WINDOW_POOLS=4" "p24x16:PT_POOL_SIZE=16777216 PT_WINDOW_POOLS=16" "p25x4:PT_POOL_SIZE=33554432 PT_WINDOW_POOLS=4" "default:"; do n=${c%%:*}; e=${c#*:}
    m=$(env $e $N render $1 --device gpu --width $4 --height $5 --spp $2 --max-depth $3 -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$4,$5,$m" >> $O/frames.csv
  done; done; echo "round $r $(el) s"; [ $(el) -gt 260 ] && break; done
python3 - $O/frames.csv <<'PY' | tee $O/frames-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['w'],r['cfg'])].append(float(r['mpaths']))
cf=["old","p24x4","p24x16","p25x4","default"]
for sc in sorted({k[:4] for k in d}):
    base=max(d.get(sc+("old",),[0])) or 1
    print(f"{sc[0]:24s} {sc[1]:>4s}spp d{sc[2]} {sc[3]}w " + " ".join(f"{c} {max(d.get(sc+(c,),[0])):7.1f}({max(d.get(sc+(c,),[0]))/base:.3f})" for c in cf))
PY
echo "== frames $(el) s"
for r in 1 2 3; do for c in "old:$OLD" "default:"; do n=${c%%:*}; e=${c#*:}
  /usr/bin/time -f "$n wall %e s, host peak %M KiB" env $e $N render scenes/cornell-box --device gpu --width 1280 --height 960 --spp 64 -o /tmp/w.exr 2>&1 | grep -E 'wall|spp in' | tr '\n' ' ' >> $O/wall.txt; echo >> $O/wall.txt
done; done; cat $O/wall.txt
echo "== wall $(el) s"
wait $PIP; cat $O/pip.txt; export PYTHONPATH=/tmp/site
B="--device gpu --variant cuda_ad_rgb --width 1280 --height 960 --spp 64 --seeds 2 --ref-spp 4096 --cache /tmp/effref"
timeout $(( 585 - $(el) )) python3 tools/bench_efficiency.py --pt $N $B --samplers pt:sobol,mitsuba:independent,mitsuba:stratified,mitsuba:multijitter,mitsuba:ldsampler --csv $O/eff.csv > $O/eff.txt 2>&1
echo "eff rc=$? $(el) s"; tail -8 $O/eff.txt
echo "== done $(el) s"
