#!/bin/bash
# Session 6, call B: the wavefront without count read-backs (sync) against the implied camera state
# alone (new): bits, speed, test_megakernel on the GPU; then error per second against Mitsuba.
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu44/libs-small.tar.xz -C /tmp/ptlib && tar xJf .gpu44/libs-tests.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1 && export PYTHONPATH=/tmp/site
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 tools/make_media_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp'); print(b.torus_scene('/tmp'))" > /dev/null
python3 tools/make_forest.py --count 1000 /tmp/forest >/dev/null 2>&1
echo "== setup $(el) s"
N=.gpu44/pt-new; S=.gpu44/pt-sync
for s in scenes/cornell-box /tmp/small-light.json tests/scenes/envmap tests/scenes/conductors tests/scenes/fog-room /tmp/forest /tmp/torus-100k.json; do
  for opt in "" "--no-compaction" "--no-sort-materials"; do
    [ -n "$opt" ] && [ $s != tests/scenes/envmap ] && continue
    $N render $s --device gpu --width 640 --height 480 --spp 16 --max-depth 64 $opt -o /tmp/b-n.exr >/dev/null 2>&1
    $S render $s --device gpu --width 640 --height 480 --spp 16 --max-depth 64 $opt -o /tmp/b-s.exr >/dev/null 2>&1
    echo "$s $opt sync/new: $(.gpu44/bench_compare_exr /tmp/b-s.exr /tmp/b-n.exr | head -1)" | tee -a $O/bits.txt
  done
done
echo "== bits $(el) s"
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2 3; do for s in "scenes/cornell-box 16 8" "tests/scenes/cornell 64 64" "/tmp/small-light.json 64 64" "tests/scenes/envmap 64 64" "tests/scenes/conductors 64 64" "/tmp/forest 16 8" "/tmp/torus-100k.json 64 64"; do set -- $s
  for c in new:$N sync:$S; do n=${c%%:*}; bin=${c#*:}
    m=$($bin render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/r.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done; done; [ $(el) -gt 150 ] && break; done
python3 - $O/speed.csv <<'PY'
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['depth'],r['cfg'])].append(float(r['mpaths']))
for sc in sorted({k[:2] for k in d}):
    a=max(d.get(sc+('new',),[0])); b=max(d.get(sc+('sync',),[0]))
    print(f"{sc[0]:26s} d{sc[1]:3s} new {a:7.1f} sync {b:7.1f} sync/new {b/a if a else 0:.3f}  (all new {d.get(sc+('new',))} sync {d.get(sc+('sync',))})")
PY
echo "== speed $(el) s"
B="--device gpu --variant cuda_ad_rgb --width 1280 --height 960 --spp 64 --seeds 2 --ref-spp 4096 --cache /tmp/effref"
timeout $(( 500 - $(el) )) python3 tools/bench_efficiency.py --pt $S $B --scenes small-light,torus-100k,cornell,env-gold,caustics,rough-metals --samplers pt:sobol,mitsuba:independent,mitsuba:stratified,mitsuba:multijitter,mitsuba:ldsampler --csv $O/eff.csv > $O/eff.txt 2>&1
echo "eff rc=$?"; grep -E "efficiency|best|pt " $O/eff.txt | tail -40
for s in /tmp/small-light.json tests/scenes/cornell; do
  echo "== sync $s" >> $O/profile.txt
  $S render $s --device gpu --width 1280 --height 960 --spp 64 --max-depth 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
done
grep -E "^==|spp in|^[a-z_]+ +[0-9]+ " $O/profile.txt
PT_TEST_DEVICE=gpu PT_BIN=$S timeout $(( 585 - $(el) )) .gpu44/tests/test_megakernel --jobs 1 2>&1 | grep -v "^pt: compiling" > $O/test-megakernel-gpu.txt; grep -E "Synthesis|Assert|FAIL" $O/test-megakernel-gpu.txt | tail -5
echo "== tests $(el) s"
echo "== done $(el) s"
