#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks, in Mitsuba 3 itself, the conventions tools/mitsuba_materials.py relies on; exits non-zero
if one does not hold (tests/references/README.md "Conventions").

  1. Environment map: with to_world = rotation about +y by 180 + theta degrees, Mitsuba's envmap
     shows what DESIGN's mapping puts in each direction (u = 0.5 + (atan2(x, -z) + theta)/2 pi,
     v = acos(y)/pi, v = 0 the top row). A 64 x 32 map with coloured marks is rendered through a
     narrow camera looking along several directions, theta = 0 and 90.
     The converted map's bilinear lookup is then compared with ours (texel centres at
     ((i + 0.5)/W, (j + 0.5)/H), wrapping in u, clamped in v) at 2000 random directions.
  2. Tangent frame and normal map: on a mesh with UVs Mitsuba's shading frame is s = dp/du and
     t = n x s, which points along increasing OBJ v for UVs that are not mirrored; its normalmap
     tilts toward s for red > 0.5 and toward t for green > 0.5 (DESIGN: OpenGL, +x along u, +y
     along v). Checked on two UV layouts by evaluating normalmap(diffuse) toward +-x and +-y.

    .venv-mitsuba/bin/python tools/mitsuba_conventions.py
"""
import math
import os
import sys
import tempfile


def check_environment(mi, np):
    w, h = 64, 32
    texels = np.full((h, w, 3), 0.05, np.float32)
    marks = {"red": ((0.5, 0.5), [1, 0, 0]), "green": ((0.75, 0.5), [0, 1, 0]),
             "blue": ((0.5, 0.1), [0, 0, 1])}
    for (u, v), colour in marks.values():
        i, j = int(u * w), int(v * h)
        texels[max(j - 2, 0):j + 2, i - 2:i + 2] = colour

    def seen(theta, d):
        up = [0, 1, 0] if abs(d[1]) < 0.9 else [0, 0, -1]
        scene = mi.load_dict({
            "type": "scene", "integrator": {"type": "path"},
            "env": {"type": "envmap", "bitmap": mi.Bitmap(texels),
                    "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], 180 + theta)},
            "camera": {"type": "perspective", "fov": 10,
                       "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 0], target=d, up=up),
                       "film": {"type": "hdrfilm", "width": 3, "height": 3, "rfilter": {"type": "box"}},
                       "sampler": {"type": "independent", "sample_count": 4}}})
        return np.array(mi.render(scene))[1, 1]

    ok = True
    for theta in (0, 90):
        for d in ([0, 0, -1], [1, 0, 0], [0, 0, 1], [-1, 0, 0], [0, 0.951, -0.309]):
            u = (0.5 + (math.atan2(d[0], -d[2]) + math.radians(theta)) / (2 * math.pi)) % 1
            v = math.acos(d[1]) / math.pi
            expected = [0.05] * 3
            for (mu, mv), colour in marks.values():
                if abs(mu - u) < 0.02 and abs(mv - v) < 0.04:
                    expected = colour
            got = seen(theta, d)
            good = np.allclose(got, expected, atol=0.02)
            ok &= good
            print(f"envmap theta {theta:2d} looking {d}: DESIGN u {u:.3f} v {v:.2f} -> {expected}, "
                  f"Mitsuba {[round(float(c), 2) for c in got]} {'ok' if good else 'WRONG'}")
    return ok


def check_environment_filter(mi, np, folder):
    """Mitsuba's envmap made by mitsuba_materials.environment_emitter against our bilinear lookup
    (cl/light/light_env.cl env_bilinear, in Python) at random directions, rotation 30."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from mitsuba_materials import environment_emitter
    rng = np.random.default_rng(1)
    w, h = 16, 8
    texels = rng.uniform(0.1, 2.0, (h, w, 3)).astype(np.float32)
    mi.Bitmap(texels).write(os.path.join(folder, "map.exr"))
    theta = 30.0
    scene = mi.load_dict({"type": "scene", "env": environment_emitter(
        {"file": "map.exr", "rotation": theta}, folder, mi, np)})
    worst = 0.0
    for _ in range(2000):
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        u = (0.5 + (math.atan2(d[0], -d[2]) + math.radians(theta)) / (2 * math.pi)) % 1
        v = math.acos(max(-1.0, min(1.0, d[1]))) / math.pi
        x, y = u * w - 0.5, v * h - 0.5
        i0, j0 = math.floor(x), math.floor(y)
        fx, fy = x - i0, y - j0
        i1, i0 = (i0 + 1) % w, i0 % w
        j1, j0 = min(j0 + 1, h - 1), max(j0, 0)
        ours = ((1 - fy) * ((1 - fx) * texels[j0, i0] + fx * texels[j0, i1]) +
                fy * ((1 - fx) * texels[j1, i0] + fx * texels[j1, i1]))
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(-d)
        theirs = np.array(scene.environment().eval(si))
        worst = max(worst, float(np.max(np.abs(theirs - ours) / ours)))
    good = worst < 1e-3
    print(f"envmap filter: Mitsuba's lookup of the converted map against our bilinear one, 2000 "
          f"directions: largest relative difference {worst:.2e} {'ok' if good else 'WRONG'}")
    return good


def check_tangent_frame(mi, np, folder):
    import drjit as dr
    ok = True
    # (u, v) at the corners of the quad z = 0 facing +z; the expected +u and +v directions.
    layouts = {"u +x, v +y": ([[0, 0], [1, 0], [1, 1], [0, 1]], [1, 0, 0], [0, 1, 0]),
               "u +y, v -x": ([[0, 1], [0, 0], [1, 0], [1, 1]], [0, 1, 0], [-1, 0, 0])}
    for name, (uv, along_u, along_v) in layouts.items():
        path = os.path.join(folder, "quad.obj")
        with open(path, "w") as f:
            f.write("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n")
            f.writelines(f"vt {a} {b}\n" for a, b in uv)
            f.write("f 1/1 2/2 3/3 4/4\n")
        scene = mi.load_dict({"type": "scene", "quad": {"type": "obj", "filename": path,
                                                         "face_normals": True}})
        si = scene.ray_intersect(mi.Ray3f([0.1, 0.2, 1], [0, 0, -1]))
        s, t = [round(c) for c in si.sh_frame.s], [round(c) for c in si.sh_frame.t]
        good = s == along_u and t == along_v
        print(f"tangent frame ({name}): s {s} t {t}, expected s along u {along_u}, t along v "
              f"{along_v} {'ok' if good else 'WRONG'}")
        ok &= good
        for channel, toward in (("red", along_u), ("green", along_v)):
            texel = [0.5, 0.5, 0.9]
            texel[0 if channel == "red" else 1] = 0.8
            bsdf = mi.load_dict({"type": "normalmap", "normalmap": {
                "type": "bitmap", "raw": True,
                "data": mi.TensorXf(np.zeros((2, 2, 3), np.float32) + np.array(texel, np.float32))},
                "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [1, 1, 1]}}})
            si.wi = [0, 0, 1]
            lit = {}
            for sign in (1, -1):
                wo = dr.normalize(mi.Vector3f([sign * toward[0], sign * toward[1], 1]))
                lit[sign] = bsdf.eval(mi.BSDFContext(), si, si.to_local(wo))[0]
            good = lit[1] > 2 * lit[-1]
            print(f"  normalmap {channel} > 0.5 tilts toward {toward}: lit {lit[1] * math.pi:.3f} "
                  f"there, {lit[-1] * math.pi:.3f} opposite {'ok' if good else 'WRONG'}")
            ok &= good
    return ok


def main():
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory(prefix="mitsuba-conventions-") as folder:
        ok = (check_environment(mi, np) & check_environment_filter(mi, np, folder) &
              check_tangent_frame(mi, np, folder))
    print("mitsuba_conventions:", "all hold" if ok else "SOME DO NOT HOLD")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
