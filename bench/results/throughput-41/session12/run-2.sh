#!/bin/bash
# Session 12, call 2. Carry .gpu45 (libs-small.tar.xz), .gpu52, .whl (Mitsuba 3.9.1 wheels).
# .gpu52/bins.tar.xz: pt-new = 28c627e (session 11's final build); pt-s12 = this session's build:
# closest hits by the speculative 2-wide walk (cl/geometry/bvh_traverse_speculative.cl), any hits
# as before. Variants of pt-s12 through PT_CL_OPTIONS: nospec (-DBVH_NO_SPECULATION: the walk of
# pt-new), novote (-DPT_EXP_NO_VOTE: while-while without the warp vote), rr64 (the default plus
# -cl-nv-maxrregcount=64). 1. bits and first builds; 2. two interleaved rounds on 8 scenes;
# 3. profiles; 4. registers of the default build's kernels (ptxas -v); 5. Mitsuba on 7 scenes.
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
mkdir -p /tmp/g52 && tar xJf .gpu52/bins.tar.xz -C /tmp/g52
OLD=/tmp/g52/pt-new NEW=/tmp/g52/pt-s12 CMP=/tmp/g52/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
M="-cl-mad-enable -cl-no-signed-zeros"
opts() { case $1 in nospec) echo "$M -DBVH_NO_SPECULATION";; novote) echo "$M -DPT_EXP_NO_VOTE";;
  rr64) echo "$M -cl-nv-maxrregcount=64";; esac; }
runv() { local v=$1; shift; case $v in old) $OLD "$@";; new) $NEW "$@";; *) PT_CL_OPTIONS="$(opts $v)" $NEW "$@";; esac; }
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors"
VS="new nospec novote rr64"
for s in $SC; do n=$(basename $s .json)
  $OLD render $s $R -o /tmp/old-$n.exr > /dev/null 2>&1
  for v in $VS; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    [ $v = new ] && grep -E "kernels [0-9.]+ s" /tmp/v.txt | sed "s/.*BVH/$n first: BVH/" | cut -c1-120
    echo "bits $n $v/old: $($CMP /tmp/old-$n.exr /tmp/$v-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"; done
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  for v in old $VS; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
done; echo "== round $r $(el) s"; done
python3 - $O/speed.csv <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(r["scene"] for r in rows):
    base = best[(scene, "old")]
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / base:.3f})" for s, v in best if s == scene))
PY
for s in tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json; do n=$(basename $s .json)
  for v in old new novote; do echo "-- profile $n $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== profiles $(el) s"
# Registers: the default build's programs for two scenes, from a cache of their own.
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do XDG_CACHE_HOME=/tmp/regcache $NEW render $s $R -o /tmp/q.exr > /dev/null 2>&1; done
export PATH=$PATH:/usr/local/cuda/bin
mkdir -p /tmp/sass
python3 - > $O/ptxas.txt 2>&1 <<'PY'
import glob, os, re, subprocess
for n, path in enumerate(sorted(p for p in glob.glob('/tmp/regcache/**', recursive=True) if os.path.isfile(p))):
    data = open(path, 'rb').read()
    i = data.find(b'//')
    if i < 0 or b'.entry' not in data:
        continue
    base = f'/tmp/sass/r{n:02d}'
    open(base + '.ptx', 'wb').write(data[i:].rstrip(b'\0'))
    print('==', path, len(data))
    r = subprocess.run(['ptxas', '-arch=sm_90', '-v', '-o', base + '.cubin', base + '.ptx'], capture_output=True, text=True)
    out = r.stderr.splitlines()
    for k, line in enumerate(out):
        if 'Compiling entry function' in line:
            name = line.split("'")[1]
            info = ' | '.join(l.split('info    : ')[-1] for l in out[k + 1:k + 4] if 'Used' in l or 'stack frame' in l)
            print(f'{name}: {info}')
        elif 'error' in line or 'fatal' in line:
            print(line)
    if any(k in data for k in (b'.entry intersect_closest', b'.entry shade_surface')):
        s = subprocess.run(['cuobjdump', '-sass', base + '.cubin'], capture_output=True, text=True)
        open(base + '.sass', 'w').write(s.stdout)
PY
tar cJf $O/sass.tar.xz -C /tmp/sass . 2>/dev/null
echo "== registers $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for s in tests/scenes/cornell /tmp/nw/normal-walls.json /tmp/small-light.json tests/scenes/cornell-sphere /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors; do
  [ $(el) -gt 500 ] && { echo "mitsuba: out of time at $s"; break; }
  python3 tools/bench_mitsuba.py $s --width 1280 --height 960 --spp 64 --max-depth 8 --reps 3 --variant cuda_ad_rgb --rr-depth 5 --csv $O/mitsuba.csv 2>&1 | grep -E "Mpaths|rror" | tail -3
done
echo "== done $(el) s"
