#!/bin/bash
# Session 7, call A: the path pool's size on the GPU (PT_POOL_SIZE sweep, same binary), same bits,
# per-stage profile; then error per second against Mitsuba with the default and the largest pool.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee $O/gpu.txt
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_forest.py --count 1000 /tmp/forest >/dev/null 2>&1
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1; echo pip rc=$? >> $O/pip.txt) &
PIP=$!
echo "== setup $(el) s"
P=.gpu45/pt-pool
SC=("/tmp/small-light.json 64 64" "tests/scenes/cornell 64 64" "scenes/cornell-box 16 8" "tests/scenes/envmap 64 64" "tests/scenes/conductors 64 64" "/tmp/torus-100k.json 64 64" "/tmp/forest 16 8")
POOLS="1048576 2097152 4194304 8388608"
echo "round,pool,scene,spp,depth,mpaths,seconds" > $O/pool.csv
for r in 1 2 3; do for s in "${SC[@]}"; do set -- $s
  for pool in $POOLS; do
    line=$(PT_POOL_SIZE=$pool $P render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/r-$r-$pool.exr 2>&1 | grep 'spp in')
    m=$(echo "$line" | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'); sec=$(echo "$line" | sed -n 's/.* spp in \([0-9.]*\) s.*/\1/p')
    echo "$r,$pool,$1,$2,$3,$m,$sec" >> $O/pool.csv
    [ $r = 1 ] && echo "$1 pool $pool: $line" >> $O/pool-lines.txt
  done
  if [ $r = 1 ]; then for pool in 1048576 4194304 8388608; do
    echo "$1 pool $pool vs 2097152: $(.gpu45/bench_compare_exr /tmp/r-1-$pool.exr /tmp/r-1-2097152.exr | head -1)" >> $O/bits.txt; done; fi
done; echo "round $r $(el) s"; [ $(el) -gt 230 ] && break; done
cat $O/bits.txt
python3 - $O/pool.csv <<'PY'
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['depth'],int(r['pool']))].append(float(r['mpaths']))
pools=sorted({k[2] for k in d})
for sc in sorted({k[:2] for k in d}):
    base=max(d.get(sc+(2097152,),[0])) or 1
    print(f"{sc[0]:28s} d{sc[1]:3s} " + " ".join(f"2^{p.bit_length()-1} {max(d.get(sc+(p,),[0])):7.1f} ({max(d.get(sc+(p,),[0]))/base:.3f})" for p in pools))
PY
echo "== pool sweep $(el) s"
for s in /tmp/small-light.json tests/scenes/cornell; do for pool in 2097152 8388608; do
  echo "== $s pool $pool" >> $O/profile.txt
  PT_POOL_SIZE=$pool $P render $s --device gpu --width 1280 --height 960 --spp 64 --max-depth 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
done; done
grep -E "^==|spp in|^[a-z_]+ +[0-9]+ " $O/profile.txt
echo "== profile $(el) s"
wait $PIP; cat $O/pip.txt; export PYTHONPATH=/tmp/site
B="--device gpu --variant cuda_ad_rgb --width 1280 --height 960 --spp 64 --seeds 2 --ref-spp 4096 --cache /tmp/effref"
timeout $(( 560 - $(el) )) python3 tools/bench_efficiency.py --pt $P $B --samplers pt:sobol,mitsuba:independent,mitsuba:stratified,mitsuba:multijitter,mitsuba:ldsampler --csv $O/eff-default.csv > $O/eff-default.txt 2>&1
echo "eff default rc=$? $(el) s"; tail -10 $O/eff-default.txt
PT_POOL_SIZE=8388608 timeout $(( 590 - $(el) )) python3 tools/bench_efficiency.py --pt $P $B --samplers pt:sobol --csv $O/eff-pool23.csv > $O/eff-pool23.txt 2>&1
echo "eff pool 2^23 rc=$? $(el) s"; tail -10 $O/eff-pool23.txt
echo "== done $(el) s"
