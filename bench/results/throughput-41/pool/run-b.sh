#!/bin/bash
# Session 7, call B: larger pools (2^22 .. 2^25), windows of 4 or 16 pools, 1280x960 and 4K.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
ls /tmp/small-light.json /tmp/torus-100k.json /tmp/forest >/dev/null || echo "scenes missing (cold machine)"
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
P=.gpu45/pt-pool
SC=("/tmp/small-light.json 64 64 1280 960" "tests/scenes/cornell 64 64 1280 960" "scenes/cornell-box 16 8 1280 960" "tests/scenes/envmap 64 64 1280 960" "/tmp/torus-100k.json 64 64 1280 960" "/tmp/forest 16 8 1280 960" "scenes/cornell-box 64 8 3840 2160" "/tmp/small-light.json 16 64 1280 960")
CF="2097152:16 4194304:16 8388608:16 8388608:4 16777216:16 16777216:4 33554432:4"
echo "round,pool,wp,scene,spp,depth,w,h,mpaths" > $O/pool2.csv
for r in 1 2; do for s in "${SC[@]}"; do set -- $s
  for c in $CF; do pool=${c%%:*}; wp=${c#*:}
    line=$(PT_POOL_SIZE=$pool PT_WINDOW_POOLS=$wp $P render $1 --device gpu --width $4 --height $5 --spp $2 --max-depth $3 -o /tmp/q.exr 2>&1 | grep 'spp in')
    m=$(echo "$line" | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$pool,$wp,$1,$2,$3,$4,$5,$m" >> $O/pool2.csv
  done; done; echo "round $r $(el) s"; [ $(el) -gt 200 ] && break; done
python3 - $O/pool2.csv <<'PY' | tee $O/pool2-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['w'],(int(r['pool']),int(r['wp'])))].append(float(r['mpaths']))
cf=sorted({k[4] for k in d})
for sc in sorted({k[:4] for k in d}):
    base=max(d.get(sc+((2097152,16),),[0])) or 1
    print(f"{sc[0]:24s} {sc[1]}spp d{sc[2]} {sc[3]}w " + " ".join(f"2^{p.bit_length()-1}x{w} {max(d.get(sc+((p,w),),[0])):7.1f}({max(d.get(sc+((p,w),),[0]))/base:.3f})" for p,w in cf))
PY
echo "== done $(el) s"
