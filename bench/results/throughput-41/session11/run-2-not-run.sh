#!/bin/bash
# NOT RUN. Five machine starts for it failed; two shortened copies (calls 3 and 4: the same steps
# without Mitsuba, on six and then four scenes, deleted since) got one more failed start and then
# too little device time. Its .gpu50/pt-new also summed the ray counts per warp with inline PTX
# (shuffles, no barrier); that part was taken out before the stop, as it never ran on NVIDIA.
# Session 11, call 2. Carry .gpu45 (libs-small.tar.xz), .gpu50, .whl (Mitsuba 3.9.1 wheels).
# .gpu50/pt-final = 24ea678 (session 10's final build); .gpu50/pt-new = this session's build:
# reverse_bits by brev, the ray counts summed per warp without barriers, and the closest hits and
# shading over every slot where the pool is full (PT_ALL_SLOTS_PERCENT: 100 default, 101 off,
# 75, 0). Bits, first builds, 2 interleaved rounds (1280x960, 64 spp, max depth 8), rays per
# path, profiles; then Mitsuba 3 cuda_ad_rgb on the issue's scene types (one round, 3 renders).
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
OLD=.gpu50/pt-final NEW=.gpu50/pt-new CMP=.gpu50/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors"
for s in $SC; do n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/new-$n.exr 2>&1 | grep -E "kernels [0-9.]+ s" | sed "s/.*BVH/$n first: BVH/" | cut -c1-120
  PT_ALL_SLOTS_PERCENT=0 $NEW render $s $R -o /tmp/all-$n.exr > /dev/null 2>&1
  echo "bits $n: new/final $($CMP /tmp/old-$n.exr /tmp/new-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-44) all/final $($CMP /tmp/old-$n.exr /tmp/all-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-44)"
done
echo "== warm $(el) s"
echo "scene,round,final,final_rays_per_path,new,new_rays_per_path,p101,p101_rpp,p75,p75_rpp,p0,p0_rpp" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  l="$n,$r,$($OLD render $s $R -o /tmp/q.exr 2>&1 | mp),$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)"
  for pc in 101 75 0; do l="$l,$(PT_ALL_SLOTS_PERCENT=$pc $NEW render $s $R -o /tmp/q.exr 2>&1 | mp)"; done
  echo "$l" >> $O/speed.csv
done; echo "== round $r $(el) s"; done
cat $O/speed.csv
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do
  for b in "$OLD" "$NEW"; do echo "-- profile $(basename $s .json) $b"; $b render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done
echo "== profiles $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for s in tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json tests/scenes/cornell-sphere /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors; do
  python3 tools/bench_mitsuba.py $s --width 1280 --height 960 --spp 64 --max-depth 8 --reps 3 --variant cuda_ad_rgb --rr-depth 5 --csv $O/mitsuba.csv 2>&1 | grep -E "Mpaths|rror" | tail -3
done
# What the driver compiled: the kernel cache's PTX through ptxas (registers, stack, spills) and
# the SASS of every program, to read here at no device time.
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
