#!/bin/bash
# Sourced by issue 41's GPU call scripts from session 14 on (the earlier run-*.sh carry their own
# copy, as they ran): NVIDIA's OpenCL ICD, pt's libraries from .gpu45, Mitsuba's wheels from .whl
# installing in the background (wait $PIP), the benchmark scenes, the render options and `mp` (a
# render's output to "Mpaths/s,rays per path"), `bits A B` (two EXRs compared bit for bit with
# $CMP, which the caller sets) and `best CSV REF` (each scene's best Mpaths/s per variant, as a
# ratio to variant REF). Sets O, T0, el, PIP, R, M, SC.
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
R="--device gpu --width 1280 --height 960 --spp 64 --max-depth 8"
M="-cl-mad-enable -cl-no-signed-zeros"
mp() { sed -n 's/.* s: \([0-9.]*\) Mpaths\/s, \([0-9.]*\) Mrays.*/\1 \2/p' | awk '{printf "%s,%.4f", $1, $2 / $1}'; }
SC="tests/scenes/cornell /tmp/small-light.json /tmp/nw/normal-walls.json tests/scenes/cornell-sphere /tmp/forest43 /tmp/torus-100k.json tests/scenes/envmap tests/scenes/conductors tests/scenes/textured"
bits() { $CMP "$1" "$2" --tolerance 0 2>&1 | tail -1 | cut -c1-200; }
best() { python3 - "$1" "$2" <<'PY'
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
best = collections.defaultdict(float)
for r in rows:
    try: best[(r["scene"], r["variant"])] = max(best[(r["scene"], r["variant"])], float(r["mpaths"]))
    except ValueError: pass
ref = sys.argv[2]
for scene in dict.fromkeys(r["scene"] for r in rows):
    b = best[(scene, ref)] or 1.0
    print(scene, " ".join(f"{v}={best[(scene, v)]:.1f}({best[(scene, v)] / b:.3f})" for s, v in best if s == scene))
PY
}
