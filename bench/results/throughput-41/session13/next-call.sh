#!/bin/bash
# Prepared at the end of session 13 for the next GPU call (not run). Carry .gpu45 (libraries),
# .gpu57 (pt-base = 65203ed, session 13's start; pt-next = 0f69a22: session 13's final build, with
# the experiment behind a flag; if .gpu57 is gone, rebuild both and strip them), .whl (Mitsuba
# 3.9.1 and Dr.Jit wheels). Variants: final (pt-next as built, = 0b87606's code), anyt (with
# -DPT_EXP_TIGHT_ANY: the any-hit visit without the closest hit's cull and order). The bits lines
# print the images' means (the room differs from 65203ed on NVIDIA within noise: call 3). Then
# Mitsuba on every scene, for the table in one call.
set -u
. bench/results/throughput-41/gpu-setup.sh
mkdir -p /tmp/g57 && tar xJf .gpu57/bins.tar.xz -C /tmp/g57
BASE=/tmp/g57/pt-base NEW=/tmp/g57/pt-next CMP=/tmp/g57/bench_compare_exr
echo "== setup $(el) s"
for s in $SC; do n=$(basename $s .json)
  $BASE render $s $R -o /tmp/base-$n.exr > /dev/null 2>&1
  $NEW render $s $R -o /tmp/final-$n.exr > /tmp/v.txt 2>&1 || tail -2 /tmp/v.txt
  grep -E "kernels [0-9.]+ s" /tmp/v.txt | sed "s/.*BVH/$n first: BVH/" | cut -c1-120
  echo "bits $n: $($CMP /tmp/base-$n.exr /tmp/final-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-150)"
  PT_CL_OPTIONS="$M -DPT_EXP_TIGHT_ANY" $NEW render $s $R -o /tmp/anyt-$n.exr > /dev/null 2>&1
  echo "bits $n anyt: $($CMP /tmp/final-$n.exr /tmp/anyt-$n.exr --tolerance 0 2>&1 | tail -1 | cut -c1-150)"
done
echo "== warm $(el) s"
echo "scene,round,variant,mpaths,rays_per_path" > $O/speed.csv
for r in 1 2; do for s in $SC; do n=$(basename $s .json)
  echo "$n,$r,base,$($BASE render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
  echo "$n,$r,final,$($NEW render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
  echo "$n,$r,anyt,$(PT_CL_OPTIONS="$M -DPT_EXP_TIGHT_ANY" $NEW render $s $R -o /tmp/q.exr 2>&1 | mp)" >> $O/speed.csv
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
  for b in $BASE $NEW; do echo "-- profile $n $(basename $b)"; $b render $s $R --profile -o /tmp/q.exr 2>&1 | grep -E "Mpaths|^[a-z_]+ +[0-9]+ +[0-9.]+ +[0-9.]+%"; done
done > $O/profiles.txt 2>&1
echo "== profiles $(el) s"
wait $PIP; cat /tmp/pip.txt
export PYTHONPATH=/tmp/site
for s in $SC; do
  [ $(el) -gt 480 ] && { echo "mitsuba: out of time at $s"; break; }
  python3 tools/bench_mitsuba.py $s --width 1280 --height 960 --spp 64 --max-depth 8 --reps 3 --variant cuda_ad_rgb --rr-depth 5 --csv $O/mitsuba.csv 2>&1 | grep -E "Mpaths|rror" | tail -3
done
echo "== done $(el) s"
