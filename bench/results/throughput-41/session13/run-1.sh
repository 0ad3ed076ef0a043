#!/bin/bash
# Session 13, call 1 of this script (the session's 2nd GPU call; the 1st ran
# session12/run-4-not-run.sh, its output is call1*). Carry .gpu45 (libraries) and .gpu55:
# pt-base = 65203ed, pt-new = ea3e121 + session12/next-experiments.patch's program_build.c hunk
# (PT_EXP_MAXRREG_<PART>: -cl-nv-maxrregcount for one program part).
# Variants (every one should give pt-base's bits):
#   new     texture features: scenes keep only the texture code they use (srgb-texture,
#           float-texture, texture-sampler, bump-map, texture);
#   tight   -DPT_EXP_TIGHT_STEP: the speculative walk's visit without the cull that cannot fire;
#   conn64  shading (CONNECT part) capped at 64 registers; core40 the walk (CORE) at 40;
#   all     tight + conn64 + core40.
# Then profiles, ptxas -v of new's programs, and whether Nsight Compute profiles OpenCL kernels.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
[ -d /tmp/ptlib/lib ] || { mkdir -p /tmp/ptlib && tar xJf .gpu45/libs-small.tar.xz -C /tmp/ptlib; }
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); b.torus_scene('/tmp')" > /dev/null
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
mkdir -p /tmp/g55 && tar xJf .gpu55/bins.tar.xz -C /tmp/g55
BASE=/tmp/g55/pt-base NEW=/tmp/g55/pt-new CMP=/tmp/g55/bench_compare_exr
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
M="-cl-mad-enable -cl-no-signed-zeros"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
runv() { local v=$1; shift; case $v in
  base) $BASE "$@";; new) $NEW "$@";;
  tight) PT_CL_OPTIONS="$M -DPT_EXP_TIGHT_STEP" $NEW "$@";;
  conn64) PT_EXP_MAXRREG_CONNECT=64 $NEW "$@";; core40) PT_EXP_MAXRREG_CORE=40 $NEW "$@";;
  all) PT_EXP_MAXRREG_CONNECT=64 PT_EXP_MAXRREG_CORE=40 PT_CL_OPTIONS="$M -DPT_EXP_TIGHT_STEP" $NEW "$@";; esac; }
VS="new tight conn64 core40 all"
echo "== setup $(el) s"
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
for s in $SC; do n=$(basename $s .json)
  $BASE render $s $R -o /tmp/base-$n.exr > /dev/null 2>&1
  for v in $VS; do runv $v render $s $R -o /tmp/$v-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
    echo "bits $n $v: $($CMP /tmp/base-$n.exr /tmp/$v-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-60)"; done
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  for v in base $VS; do echo "$n,$r,$v,$(runv $v render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv; done
done; echo "== round $r $(el) s"; done
python3 - $O/speed.csv <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
for scene in dict.fromkeys(r["scene"] for r in rows):
    base = best[(scene, "base")]
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / base:.3f})" for s, v in best if s == scene))
PY
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do n=$(basename $s .json)
  for v in base new all; do echo "-- profile $n $v"; runv $v render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== profiles $(el) s"
for s in tests/scenes/cornell /tmp/nw/normal-walls.json; do XDG_CACHE_HOME=/tmp/regcache $NEW render $s $R -o /tmp/q.exr > /dev/null 2>&1; done
export PATH=$PATH:/usr/local/cuda/bin
python3 - > $O/ptxas.txt 2>&1 <<'PY'
import glob, os, subprocess
for n, path in enumerate(sorted(p for p in glob.glob('/tmp/regcache/**', recursive=True) if os.path.isfile(p))):
    data = open(path, 'rb').read()
    i = data.find(b'//')
    if i < 0 or b'.entry' not in data:
        continue
    base = f'/tmp/r{n:02d}'
    open(base + '.ptx', 'wb').write(data[i:].rstrip(b'\0'))
    print('==', path, len(data))
    r = subprocess.run(['ptxas', '-arch=sm_90', '-v', '-o', base + '.cubin', base + '.ptx'], capture_output=True, text=True)
    out = r.stderr.splitlines()
    for k, line in enumerate(out):
        if 'Compiling entry function' in line:
            info = ' | '.join(l.split('info    : ')[-1] for l in out[k + 1:k + 4] if 'Used' in l or 'stack frame' in l)
            print(f"{line.split(chr(39))[1]}: {info}")
    if b'.entry shade_surface' in data:
        s = subprocess.run(['cuobjdump', '-sass', base + '.cubin'], capture_output=True, text=True).stdout
        print('shade_surface and others: SASS instructions', sum(1 for l in s.splitlines() if l.strip().startswith('/*') and '*/' in l[:12]))
PY
echo "== registers $(el) s"
NCU=$(command -v ncu || ls /opt/nvidia/nsight-compute/*/ncu /usr/local/cuda/bin/ncu 2>/dev/null | head -1)
echo "ncu: $NCU"
[ -n "$NCU" ] && timeout 120 $NCU --target-processes all -k regex:'intersect_closest|shade_surface' -c 4 \
  --section SpeedOfLight --section Occupancy --section WarpStateStats --section SchedulerStats \
  $NEW render tests/scenes/cornell $R --spp 4 -o /tmp/q.exr > $O/ncu.txt 2>&1; echo "ncu rc=$? $(wc -l < $O/ncu.txt) lines"
echo "== done $(el) s"
