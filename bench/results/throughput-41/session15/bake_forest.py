#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# bake_forest.py IN OUT: the forest of tools/make_forest.py with every instance baked into one OBJ
# in world space (usemtl kept): a one-level scene equal to the instanced one, to time what
# instancing costs beyond the flat BVH (call-d.sh). Pure Python, no numpy needed.
import json, math, os, shutil, sys
base, outdir = sys.argv[1], sys.argv[2]
os.makedirs(outdir, exist_ok=True)
scene = json.load(open(base + "/scene.json"))
def mat_mul(a, b): return [[sum(a[i][k]*b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
def eye(): return [[float(i == j) for j in range(4)] for i in range(4)]
def xform(ops):
    m = eye()
    for op in ops:
        (name, v), = op.items(); s = eye()
        if name == "translate": s[0][3], s[1][3], s[2][3] = v
        elif name == "scale":
            sc = [v]*3 if isinstance(v, (int, float)) else v
            for i in range(3): s[i][i] = sc[i]
        elif name == "rotate":
            ax = v["axis"]; n = math.sqrt(sum(x*x for x in ax)); x, y, z = [c/n for c in ax]
            a = math.radians(v["angle"]); K = [[0, -z, y], [z, 0, -x], [-y, x, 0]]
            K2 = [[sum(K[i][k]*K[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
            for i in range(3):
                for j in range(3): s[i][j] = (i == j) + math.sin(a)*K[i][j] + (1-math.cos(a))*K2[i][j]
        m = mat_mul(s, m)
    return m
o = open(outdir + "/flat.obj", "w"); o.write("mtllib forest.mtl\n"); nv = 0
for obj in scene["objects"]:
    m = xform(obj.get("transform", [])); vs = 0
    for line in open(base + "/" + obj["obj"]):
        t = line.split()
        if not t: continue
        if t[0] == "v":
            v = [float(x) for x in t[1:4]]
            w = [sum(m[i][j]*v[j] for j in range(3)) + m[i][3] for i in range(3)]
            o.write("v %.9g %.9g %.9g\n" % tuple(w)); vs += 1
        elif t[0] == "usemtl": o.write(line)
        elif t[0] == "f":
            o.write("f " + " ".join(str(int(x.split("/")[0]) + nv) for x in t[1:]) + "\n")
    nv += vs
shutil.copy(base + "/forest.mtl", outdir)
scene["objects"] = [{"obj": "flat.obj"}]
json.dump(scene, open(outdir + "/scene.json", "w"), indent=1)
