#!/bin/bash
# Session 15, call E: what the forest's ground quad costs. Its two triangles span the scene, so
# the rays that leave the ground start inside the ground's large boxes. The forest against copies
# whose ground is an N x N grid of quads in the same plane (grid_ground.py: the same surface), at
# the settings (1280x960, 256 spp, max depth 8) with the roulette from the third vertex,
# 3 interleaved rounds, then the stage profiles; and the same with every instance baked into one
# mesh (bake_forest.py, call D's 1.018). Carry .gpu45 and .gpu59 (pt-final: session 14's build).
set -u
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g59 && tar xJf .gpu59/bins.tar.xz -C /tmp/g59
FINAL=/tmp/g59/pt-final CMP=/tmp/g59/bench_compare_exr
D=bench/results/throughput-41/session15
for n in 4 16 64; do python3 $D/grid_ground.py /tmp/forest43 /tmp/g$n $n; done
python3 $D/bake_forest.py /tmp/forest43 /tmp/baked && python3 $D/bake_forest.py /tmp/g16 /tmp/baked-g16
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
scene_of() { case $1 in inst) echo /tmp/forest43;; baked) echo /tmp/baked;; bg16) echo /tmp/baked-g16;; *) echo /tmp/$1;; esac; }
V="inst g4 g16 g64 baked bg16"
run3() { PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" $FINAL render $(scene_of $1) $R "${@:2}"; }
for v in $V; do run3 $v -o /tmp/$v.exr 2>&1 | grep -E "triangles|Mpaths" | cut -c1-160; done
for v in g4 g16 g64 baked bg16; do echo "means inst/$v: $(bits /tmp/inst.exr /tmp/$v.exr)"; done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/ground.csv
for r in 1 2 3; do for v in $V; do
  echo "forest43,$r,$v,$(run3 $v -o /tmp/q.exr 2>&1 | mp)" >> $O/ground.csv
done; echo "== round $r $(el) s"; done
cat $O/ground.csv
best $O/ground.csv inst
for v in $V; do echo "-- profile $v"; run3 $v --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done > $O/profiles.txt 2>&1
cat $O/profiles.txt
echo "== done $(el) s"
