#!/bin/bash
# Session 15, call D: what instancing costs the forest beyond its flat BVH. The 43-instance forest
# (the flat BVH over its instances, shading through them: features analytic, instances) against
# the same forest baked into one world-space OBJ by bake_forest.py (one level: feature analytic),
# at the settings (1280x960, 256 spp, max depth 8), roulette from the third vertex (rr3)
# and as shipped (rr5); 3 interleaved rounds, then each one's stage profile. Carry .gpu45 and
# .gpu59 (pt-final: session 14's final build).
set -u
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g59 && tar xJf .gpu59/bins.tar.xz -C /tmp/g59
FINAL=/tmp/g59/pt-final CMP=/tmp/g59/bench_compare_exr
python3 bench/results/throughput-41/session15/bake_forest.py /tmp/forest43 /tmp/baked43
R="--device gpu --width 1280 --height 960 --spp 256 --max-depth 8"
runv() { local v=$1; shift; case $v in
  inst3|baked3) PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" $FINAL "$@";;
  inst5|baked5) $FINAL "$@";;
  bfused3) PT_CONNECT_IN_SHADING=1 PT_CL_OPTIONS="$M -DPT_ROULETTE_DEPTH=3u" $FINAL "$@";; esac; }
scene_of() { case $1 in inst*) echo /tmp/forest43;; *) echo /tmp/baked43;; esac; }
V="inst3 baked3 inst5 baked5 bfused3"
for v in $V; do runv $v render $(scene_of $v) $R -o /tmp/$v.exr 2>&1 | grep -E "kernels|Mpaths" | cut -c1-200; done
echo "means inst3/baked3: $(bits /tmp/inst3.exr /tmp/baked3.exr)"
echo "means inst5/baked5: $(bits /tmp/inst5.exr /tmp/baked5.exr)"
echo "bits baked3/bfused3: $(bits /tmp/baked3.exr /tmp/bfused3.exr)"
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/baked.csv
for r in 1 2 3; do for v in $V; do
  echo "forest43,$r,$v,$(runv $v render $(scene_of $v) $R -o /tmp/q.exr 2>&1 | mp)" >> $O/baked.csv
done; echo "== round $r $(el) s"; done
cat $O/baked.csv
best $O/baked.csv inst3
for v in inst3 baked3 inst5 baked5; do echo "-- profile $v"
  runv $v render $(scene_of $v) $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done > $O/profiles.txt 2>&1
cat $O/profiles.txt
echo "== done $(el) s"
