#!/bin/bash
# Session 11, call 4 (calls 2 and 3 never started: seven machine starts failed; too little device
# time was left for them): call 3 on four scenes. Carry .gpu45 (libs-small.tar.xz), .gpu50.
# .gpu50/pt-final = 24ea678; .gpu50/pt-new = 3a7cd01: reverse_bits by brev, ray counts summed
# per warp, closest hits and shading over every slot of a full pool (PT_ALL_SLOTS_PERCENT 100;
# 101 turns it off, 0 takes every step over every slot). Bits; 2 interleaved rounds, 1280x960,
# 64 spp, max depth 8 (Mpaths/s, rays per path); the driver's PTX through ptxas and its SASS.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
OLD=.gpu50/pt-final NEW=.gpu50/pt-new CMP=.gpu50/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere"
for s in $SC; do n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr > /dev/null 2>&1
  echo "bits $n: new/final $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-44)"
done
echo "== warm $(el) s"
echo "scene,round,final,final_rays_per_path,new,new_rays_per_path,p101,p101_rpp" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  echo "$n,$r,$($OLD render $s $R -o /tmp/q.exr 2>&1 | mp),$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp),$(PT_ALL_SLOTS_PERCENT=101 $NEW render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
done; echo "== round $r $(el) s"; done
cat $O/speed.csv
for b in "$OLD" "$NEW"; do echo "-- profile cornell $b"; $b render tests/scenes/cornell $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
echo "== profiles $(el) s"
export PATH=$PATH:/usr/local/cuda/bin
mkdir -p /tmp/sass
python3 - > $O/ptxas.txt 2>&1 <<'PY'
import glob, os, subprocess
for n, path in enumerate(sorted(p for p in glob.glob('/tmp/ptcache/**', recursive=True) if os.path.isfile(p))):
    data = open(path, 'rb').read()
    i = data.find(b'//')
    if i < 0 or b'.entry' not in data:
        continue
    base = f'/tmp/sass/p{n:02d}'
    open(base + '.ptx', 'wb').write(data[i:])
    kernels = [l.split()[-1].split('(')[0] for l in data[i:].decode(errors='replace').splitlines() if '.entry' in l]
    print('==', path, len(data), ' '.join(kernels))
    r = subprocess.run(['ptxas', '-arch=sm_90', '-v', '-o', base + '.cubin', base + '.ptx'], capture_output=True, text=True)
    print(r.stderr[-4000:])
    s = subprocess.run(['cuobjdump', '-sass', base + '.cubin'], capture_output=True, text=True)
    open(base + '.sass', 'w').write(s.stdout)
PY
tar cJf $O/sass.tar.xz -C /tmp/sass . 2>/dev/null; ls -la $O
echo "== done $(el) s"
