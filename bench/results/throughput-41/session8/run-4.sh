#!/bin/bash
# Session 8, call 4: the maths options on NVIDIA. Default (mad, no signed zeros, correctly rounded
# division and square root) against the same without correctly rounded division and square root
# (nocr) and with no options at all (none): speed (interleaved), stages, image statistics.
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
[ -d /tmp/forest43 ] || python3 tools/make_forest.py --count 42 /tmp/forest43 >/dev/null 2>&1
python3 tools/make_bench_scenes.py --normal-walls /tmp/nw > /dev/null
(python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1; echo pip rc=$? >> $O/pip.txt) &
PIP=$!
H=.gpu45/pt-head C=.gpu46/bench_compare_exr
DEF="-cl-mad-enable -cl-no-signed-zeros -cl-fp32-correctly-rounded-divide-sqrt"
NOCR="-cl-mad-enable -cl-no-signed-zeros"
echo "== setup $(el) s"
SC=("/tmp/small-light.json 64 64" "tests/scenes/cornell 64 64" "scenes/cornell-box 64 8" "tests/scenes/envmap 64 64" "tests/scenes/conductors 64 64" "/tmp/torus-100k.json 64 64" "/tmp/forest43 16 8" "tests/scenes/cornell-sphere 64 64" "/tmp/nw/normal-walls.json 64 8")
for s in "${SC[@]}"; do set -- $s
  $H render $1 --device gpu --width 1280 --height 960 --spp 16 --max-depth $3 -o /tmp/b-d.exr > /dev/null 2>&1
  PT_CL_OPTIONS="$NOCR" $H render $1 --device gpu --width 1280 --height 960 --spp 16 --max-depth $3 -o /tmp/b-n.exr > /dev/null 2>&1
  echo "$1 nocr/default: $($C /tmp/b-n.exr /tmp/b-d.exr | head -1)" | tee -a $O/images.txt
done
echo "== images $(el) s"
for s in scenes/cornell-box /tmp/small-light.json /tmp/forest43; do for c in "default:$DEF" "nocr:$NOCR"; do n=${c%%:*}; e=${c#*:}
  echo "-- $s $n" >> $O/profile.txt
  PT_CL_OPTIONS="$e" $H render $s --device gpu --width 1280 --height 960 --spp 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
done; done
echo "== profile $(el) s"
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2 3; do for s in "${SC[@]}"; do set -- $s
  for c in "default:$DEF" "nocr:$NOCR" "none:-DPT_NONE=1"; do n=${c%%:*}; e=${c#*:}
    m=$(PT_CL_OPTIONS="$e" $H render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/q.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done; done; echo "round $r $(el) s"; [ $(el) -gt 300 ] && break; done
python3 - $O/speed.csv <<'PY' | tee $O/speed-summary.txt
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['spp'],r['depth'],r['cfg'])].append(float(r['mpaths']))
cf=["default","nocr","none"]
for sc in sorted({k[:3] for k in d}):
    base=max(d.get(sc+("default",),[0])) or 1
    print(f"{sc[0]:30s} {sc[1]:>3s}spp d{sc[2]:>2s} " + " ".join(f"{c} {max(d.get(sc+(c,),[0])):7.1f}({max(d.get(sc+(c,),[0]))/base:.3f})" for c in cf))
PY
grep -E "^--|intersect_closest|shade_surface|intersect_shadow|generate|compact|Mpaths" $O/profile.txt | head -60
wait $PIP; cat $O/pip.txt
for c in "default:$DEF" "nocr:$NOCR"; do n=${c%%:*}; e=${c#*:}
  PT_CL_OPTIONS="$e" PYTHONPATH=/tmp/site PYTHON=python3 PT=$H DEVICE=gpu WIDTH=1280 HEIGHT=960 SPP=64 DEPTH=8 ROUNDS=1 \
    timeout $(( 590 - $(el) )) tools/bench-vs-mitsuba.sh /tmp/nw/normal-walls.json -o $O/nw-$n 2>&1 | grep -A4 renderer
done
echo "== done $(el) s"
