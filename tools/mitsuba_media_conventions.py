#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks, in Mitsuba 3 itself, what tools/mitsuba_media.py and tools/mitsuba_lights.py rely on;
exits non-zero if one does not hold (tests/references/README.md "Media").

  1. gridvolume with use_grid_bbox: the .vol header's box places the grid, and the lookup is
     DESIGN's: trilinear between voxel centres at the voxels' middles ((i + 0.5) / n of the box),
     clamped to the edge values. A random 5 x 4 x 3 grid is looked up at 500 random points of its
     box (and a margin around it) and compared with that formula.
  2. heterogeneous: no medium outside the grid's box, even inside the shape it fills; inside it,
     transmittance exp(-scale x density x length). Rendered: a camera looks through a null-BSDF
     cube whose interior is a grid covering only its left half (albedo 0), at a white sky.
  3. homogeneous, as translated (sigma_t / max in sigma_t, max in scale): chromatic transmittance
     exp(-sigma_t d) per channel through the same cube.
  4. hg: g > 0 scatters forward (wi points back along the ray, as pbrt's), with the HG density.
  5. spot: full intensity inside beam_width, linear in angle to 0 at cutoff_angle (our falloff).

    .venv-mitsuba/bin/python tools/mitsuba_media_conventions.py
"""
import math
import os
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_media import homogeneous  # noqa: E402
from mitsuba_vol import write_vol  # noqa: E402


def ours_trilinear(np, grid, lo, hi, p):
    """DESIGN's lookup: grid[z, y, x], voxel centres at the voxels' middles, clamped."""
    n = np.array(grid.shape[::-1])
    f = (np.asarray(p) - lo) / (hi - lo) * n - 0.5
    f = np.clip(f, 0, n - 1)
    i0 = np.minimum(np.floor(f).astype(int), n - 2)
    t = f - i0
    v = 0.0
    for corner in range(8):
        o = np.array([(corner >> k) & 1 for k in range(3)])
        w = np.prod(np.where(o == 1, t, 1 - t))
        x, y, z = i0 + o
        v += w * grid[z, y, x]
    return v


def check_grid_lookup(mi, np, temp):
    rng = np.random.default_rng(7)
    grid = rng.random((3, 4, 5)).astype(np.float32)  # z, y, x
    lo, hi = np.array([-1.0, 0.5, 2.0]), np.array([1.5, 1.5, 2.6])
    path = os.path.join(temp, "probe.vol")
    write_vol(path, (5, 4, 3), lo.tolist(), hi.tolist(), [float(v) for v in grid.ravel()])
    vol = mi.load_dict({"type": "gridvolume", "filename": path, "use_grid_bbox": True})
    worst = 0.0
    for _ in range(500):
        p = lo - 0.1 * (hi - lo) + rng.random(3) * 1.2 * (hi - lo)
        it = mi.Interaction3f()
        it.p = mi.Point3f(*p)
        worst = max(worst, abs(float(vol.eval_1(it)) - ours_trilinear(np, grid, lo, hi, p)))
    ok = worst < 1e-5
    print(f"gridvolume use_grid_bbox: largest difference from DESIGN's trilinear lookup {worst:.2e} "
          f"{'ok' if ok else 'WRONG'}")
    return ok


def transmittance_scene(mi, medium, x):
    """A 1 x 1 pixel camera at (x, 0, 3) looking along -z through a null-BSDF cube [-1, 1]^3
    filled with `medium`, at a constant sky of radiance 1; volpath, no emitters hidden."""
    return mi.load_dict({
        "type": "scene", "integrator": {"type": "volpath", "max_depth": 2},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": [1, 1, 1]}},
        "cube": {"type": "cube", "bsdf": {"type": "null"}, "interior": medium},
        "camera": {"type": "perspective", "fov": 0.01,
                   "to_world": mi.ScalarTransform4f().look_at(origin=[x, 0, 3], target=[x, 0, 0],
                                                              up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": 1, "height": 1, "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": 1 << 18}}})


def check_media(mi, np, temp):
    ok = True
    path = os.path.join(temp, "half.vol")
    write_vol(path, (2, 2, 2), [-1, -1, -1], [0, 1, 1], [1.0] * 8)  # the cube's left half, density 1
    grid = {"type": "heterogeneous", "scale": 0.7, "albedo": 0.0,
            "sigma_t": {"type": "gridvolume", "filename": path, "use_grid_bbox": True}}
    for x, expected in ((-0.5, math.exp(-0.7 * 2)), (0.5, 1.0)):
        got = float(np.array(mi.render(transmittance_scene(mi, grid, x)))[0, 0, 0])
        good = abs(got - expected) < 0.02 * expected  # the estimate's noise is about 0.5 %
        ok &= good
        print(f"heterogeneous, camera at x = {x:+.1f}: transmittance {got:.4f}, expected {expected:.4f} "
              f"{'ok' if good else 'WRONG'}")
    sigma = [0.2, 0.9, 1.6]
    medium = homogeneous({"type": "homogeneous", "sigma_a": sigma, "sigma_s": 0.0}, "probe")
    medium["sigma_t"] = mi.ScalarColor3f(*medium["sigma_t"]["value"])
    medium["albedo"] = mi.ScalarColor3f(*medium["albedo"]["value"])
    got = np.array(mi.render(transmittance_scene(mi, medium, 0.0)))[0, 0]
    expected = np.exp(-2 * np.array(sigma))
    # Mitsuba samples distances in one channel and weights the others (about 1 % noise here).
    good = np.allclose(got, expected, rtol=0.03)
    ok &= good
    print(f"homogeneous sigma_t {sigma} as translated: transmittance {np.round(got, 4)}, expected "
          f"{np.round(expected, 4)} {'ok' if good else 'WRONG'}")
    return ok


def check_hg(mi, np):
    g = 0.5
    phase = mi.load_dict({"type": "hg", "g": g})
    mei = mi.MediumInteraction3f()
    mei.wi = mi.Vector3f(0, 0, 1)  # the ray travelled along -z
    mei.sh_frame = mi.Frame3f(mei.wi)
    ctx = mi.PhaseFunctionContext(None)
    ok = True
    for wo, cos_scatter in (([0, 0, -1], 1.0), ([0, 0, 1], -1.0), ([1, 0, 0], 0.0)):
        got = float(phase.eval_pdf(ctx, mei, mi.Vector3f(*wo))[1])
        expected = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos_scatter) ** 1.5)
        good = abs(got - expected) < 1e-5 * expected
        ok &= good
        print(f"hg g {g}: scattering angle cosine {cos_scatter:+.0f}: {got:.5f}, pbrt's HG {expected:.5f} "
              f"{'ok' if good else 'WRONG'}")
    return ok


def check_spot(mi, np):
    from mitsuba_lights import emitters
    cone, falloff = 25.0, 18.0
    (spot,) = emitters({"lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0],
                                    "intensity": 2.0, "cone_angle": cone, "falloff_angle": falloff}]},
                       mi).values()
    light = mi.load_dict(spot)
    ok = True
    for angle in (0.0, 10.0, 17.9, 20.0, 21.5, 24.0, 26.0):
        a = math.radians(angle)
        it = mi.Interaction3f()
        it.p = mi.Point3f(math.sin(a), -math.cos(a), 0.0)  # distance 1
        _, value = light.sample_direction(it, mi.Point2f(0.5, 0.5))
        got = float(value[0])
        profile = 1.0 if angle <= falloff else max(0.0, (cone - angle) / (cone - falloff))
        good = abs(got - 2.0 * profile) < 1e-3
        ok &= good
        print(f"spot at {angle:4.1f} degrees: {got:.4f}, ours {2.0 * profile:.4f} "
              f"{'ok' if good else 'WRONG'}")
    return ok


def main():
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory(prefix="mitsuba-media-") as temp:
        ok = check_grid_lookup(mi, np, temp)
        ok &= check_media(mi, np, temp)
    ok &= check_hg(mi, np)
    ok &= check_spot(mi, np)
    print("all media conventions hold" if ok else "some conventions do NOT hold")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
