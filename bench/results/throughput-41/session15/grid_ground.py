#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# grid_ground.py IN OUT N: a copy of the forest of tools/make_forest.py whose ground quad (two
# triangles across the whole scene) is an N x N grid of quads in the same plane, wound the same
# way: the same surface, so the same image up to rounding, but a BVH whose ground boxes are small
# (call-e.sh: what the ground's one large box costs the rays that leave it).
import os, shutil, sys
src, out, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
shutil.copytree(src, out, dirs_exist_ok=True)
lines = open(os.path.join(src, "ground.obj")).read().split("\n")
vs = [[float(x) for x in l.split()[1:4]] for l in lines if l.startswith("v ")]
lo, hi = vs[0][0], vs[2][0]  # corners (lo, 0, lo), (lo, 0, hi), (hi, 0, hi), (hi, 0, lo)
assert vs == [[lo, 0, lo], [lo, 0, hi], [hi, 0, hi], [hi, 0, lo]], vs
head = [l for l in lines if l and not l.startswith(("v ", "f "))]
at = lambda i: lo + (hi - lo) * i / n if i < n else hi
with open(os.path.join(out, "ground.obj"), "w") as f:
    f.write("\n".join(head) + "\n")
    for i in range(n + 1):
        for k in range(n + 1):
            f.write("v %.9g 0 %.9g\n" % (at(i), at(k)))
    v = lambda i, k: i * (n + 1) + k + 1
    for i in range(n):
        for k in range(n):
            # as the quad: (lo, lo), (lo, hi), (hi, hi) and (lo, lo), (hi, hi), (hi, lo)
            f.write("f %d %d %d\nf %d %d %d\n" % (v(i, k), v(i, k + 1), v(i + 1, k + 1),
                                                  v(i, k), v(i + 1, k + 1), v(i + 1, k)))
