#!/bin/bash
# Session 6, call A: can ncu read NVIDIA OpenCL kernels? Per-kernel counters of the hot stages;
# the shadow_contribution stores A/B (before = 24d6d74, after = HEAD).
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu44/libs-small.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv,noheader | tee $O/gpu.txt
python3 tools/make_material_scenes.py tests/scenes >/dev/null 2>&1
python3 -c "
import sys; sys.path.insert(0,'tools')
import bench_efficiency as b
b.small_light_scene('/tmp')" > /dev/null
python3 tools/make_forest.py --count 1000 /tmp/forest >/dev/null 2>&1
which ncu; ncu --version | tail -1
echo "== setup $(el) s"
N=.gpu44/pt; B=.gpu44/pt-before; W=.gpu44/pt-new
for s in scenes/cornell-box tests/scenes/cornell /tmp/small-light.json tests/scenes/envmap /tmp/forest; do
  $N render $s --device gpu --width 160 --height 120 --spp 8 --max-depth 64 -o /tmp/b-new.exr >/dev/null 2>&1
  $B render $s --device gpu --width 160 --height 120 --spp 8 --max-depth 64 -o /tmp/b-old.exr >/dev/null 2>&1
  echo "$s head/before: $(.gpu44/bench_compare_exr /tmp/b-new.exr /tmp/b-old.exr | head -1)" | tee -a $O/bits.txt
  $W render $s --device gpu --width 160 --height 120 --spp 8 --max-depth 64 -o /tmp/b-w.exr >/dev/null 2>&1
  echo "$s new/head: $(.gpu44/bench_compare_exr /tmp/b-w.exr /tmp/b-new.exr | head -1)" | tee -a $O/bits.txt
  PT_MEGAKERNEL=1 $W render $s --device gpu --width 160 --height 120 --spp 8 --max-depth 64 -o /tmp/b-wm.exr >/dev/null 2>&1
  PT_EXP_IMPLY_DIRECTION=1 $W render $s --device gpu --width 160 --height 120 --spp 8 --max-depth 64 -o /tmp/b-wd.exr >/dev/null 2>&1
  echo "$s new dir/head: $(.gpu44/bench_compare_exr /tmp/b-wd.exr /tmp/b-new.exr | head -1)" | tee -a $O/bits.txt
  echo "$s new megakernel/head: $(.gpu44/bench_compare_exr /tmp/b-wm.exr /tmp/b-new.exr | head -1)" | tee -a $O/bits.txt
done
echo "== bits (and warm caches) $(el) s"
echo "round,cfg,scene,spp,depth,mpaths" > $O/speed.csv
for r in 1 2 3; do for s in "scenes/cornell-box 16 8" "tests/scenes/cornell 64 64" "/tmp/small-light.json 64 64" "tests/scenes/envmap 64 64" "/tmp/forest 16 8"; do set -- $s
  for c in before:$B head:$N new:$W dir:$W; do n=${c%%:*}; bin=${c#*:}; e=; [ $n = dir ] && e=PT_EXP_IMPLY_DIRECTION=1
    m=$(env $e $bin render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/r.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
    echo "$r,$n,$1,$2,$3,$m" >> $O/speed.csv
  done; done; [ $(el) -gt 200 ] && break; done
python3 - $O/speed.csv <<'PY'
import csv,sys,collections
d=collections.defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r['mpaths']: d[(r['scene'],r['depth'],r['cfg'])].append(float(r['mpaths']))
for sc in sorted({k[:2] for k in d}):
    b=max(d.get(sc+('before',),[0])); h=max(d.get(sc+('head',),[0])); w=max(d.get(sc+('new',),[0])); x=max(d.get(sc+('dir',),[0]))
    print(f"{sc[0]:26s} d{sc[1]:3s} before {b:7.1f} head {h:7.1f} new {w:7.1f} dir {x:7.1f} head/before {h/b if b else 0:.3f} new/head {w/h if h else 0:.3f} dir/head {x/h if h else 0:.3f}")
PY
echo "== speed $(el) s"
for r in 1 2; do for s in "/tmp/small-light.json 64 64" "tests/scenes/cornell 64 64" "scenes/cornell-box 16 8"; do set -- $s
  for mk in 0 1; do m=$(PT_MEGAKERNEL=$mk $N render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/r.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p'); echo "megakernel=$mk $1 d$3: $m" | tee -a $O/megakernel.txt; done; done; done
echo "== megakernel $(el) s"
X=.gpu44/pt-exp
for r in 1 2 3; do for s in "/tmp/small-light.json 64 64" "tests/scenes/cornell 64 64" "scenes/cornell-box 16 8" "tests/scenes/envmap 64 64"; do set -- $s
  f=/tmp/cnt-$(basename $1).bin; rm -f $f
  a=$(PT_EXP_COUNTS=$f $X render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/s1.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
  b=$(PT_EXP_COUNTS=$f PT_EXP_REPLAY=1 $X render $1 --device gpu --width 1280 --height 960 --spp $2 --max-depth $3 -o /tmp/s2.exr 2>&1 | sed -n 's/.* s: \([0-9.]*\) Mpaths.*/\1/p')
  echo "sync-cost $1 d$3: synced $a replayed $b counts $(( $(stat -c %s $f) / 4 )) $(.gpu44/bench_compare_exr /tmp/s1.exr /tmp/s2.exr | head -1)" | tee -a $O/sync-cost.txt
done; done
echo "== sync cost $(el) s"
for s in /tmp/small-light.json tests/scenes/cornell /tmp/forest; do
  echo "== dir $s" >> $O/profile.txt
  PT_EXP_IMPLY_DIRECTION=1 $W render $s --device gpu --width 1280 --height 960 --spp 16 --max-depth 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
  echo "== new $s" >> $O/profile.txt
  $W render $s --device gpu --width 1280 --height 960 --spp 16 --max-depth 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
  echo "== head $s" >> $O/profile.txt
  $N render $s --device gpu --width 1280 --height 960 --spp 16 --max-depth 64 --profile -o /tmp/p.exr >> $O/profile.txt 2>&1
done
grep -E "^==|spp in|^[a-z_]+ +[0-9]+ " $O/profile.txt
timeout $(( 570 - $(el) < 90 ? 570 - $(el) : 90 )) ncu --clock-control none --section SpeedOfLight --launch-count 6 $N render /tmp/small-light.json --device gpu --width 320 --height 240 --spp 1 -o /tmp/x.exr > $O/ncu-probe.txt 2>&1
echo "ncu rc=$?"; grep -E "==PROF==|==ERR|==WARN|^  [a-z_]+ \(|Duration|Memory Throughput|Compute \(SM\)" $O/ncu-probe.txt | head -30
echo "== ncu probe $(el) s"
if grep -q "shade_surface\|generate_camera_rays\|intersect_closest" $O/ncu-probe.txt; then
  for s in "/tmp/small-light.json small" "scenes/cornell-box cornell" "/tmp/forest forest"; do set -- $s
    timeout $(( (580 - $(el)) / 3 )) ncu --clock-control none -k regex:'^(generate_camera_rays|intersect_closest|shade_surface|intersect_shadow|compact_paths)$' \
      --launch-skip 10 --launch-count 5 --section SpeedOfLight --section MemoryWorkloadAnalysis --section Occupancy \
      --section LaunchStats --section WarpStateStats --section SchedulerStats --section ComputeWorkloadAnalysis \
      $N render $1 --device gpu --width 1280 --height 960 --spp 2 --max-depth 64 -o /tmp/x.exr > $O/ncu-$2.txt 2>&1
    echo "ncu $2 rc=$? $(el) s"
  done
fi
echo "== ncu $(el) s"
echo "== done $(el) s"
