#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Error per second: pt's samplers against Mitsuba 3's on the same scenes (issue 34).

For each scene: a high-spp Mitsuba reference (independent sampler, rendered once and cached in
--cache), then SEEDS renders of each renderer and sampler at --spp: pt's sobol and independent
(`pt render`, its own reported render time: no loading, no kernel compilation), Mitsuba's
independent, stratified, multijitter and ldsampler (mi.render after a warm-up render, so Dr.Jit's
compilation stays out). Error: relMSE = mean over pixels and channels of (a - ref)^2 / (ref^2 +
0.01); efficiency = 1 / (relMSE x seconds). Writes one CSV row per render (--csv) and prints per
scene the mean relMSE, time and efficiency of each, and pt's best efficiency over Mitsuba's best.

Scenes (SCENES below): a Cornell box; glass and mirror spheres (caustics); a small light (written
here: a 4 cm lamp over a box and a floor); an environment map over rough gold; rough metals; a
100k-triangle torus in a lit box (tools/make_bench_scenes.py's). Every scene is converted for
Mitsuba by tools/mitsuba_reference.py, the converter of the committed references. The media scenes
(issue 40; not in the default list: --scenes media picks them all) are tools/make_media_scenes.py's
reference scenes, written here: fog-room, smoke, liquid, subsurface; Mitsuba renders them with
volpath. Each row also gives Mpaths/s (width x height x spp / seconds).

  PYTHON tools/bench_efficiency.py [--pt build/pt] [--device cpu|gpu] [--variant llvm_ad_rgb]
      [--width 160 --height 120] [--spp 64] [--seeds 4] [--ref-spp 4096] [--max-depth 64]
      [--scenes cornell,caustics,...|media] [--cache DIR] [--csv FILE]
      [--max-depth N|scene] [--rr-depth N] [--samplers pt:sobol,mitsuba:independent]

PYTHON imports mitsuba and numpy (.venv-mitsuba, or on a machine without network wheels fetched
elsewhere with `pip download mitsuba==3.9.1 numpy -d wheels` and installed with `pip install
--no-index --find-links wheels --target pydeps mitsuba numpy`). It runs from a checkout or from a
pt bundle (tools/bundle.sh: bin/pt, tools/, tests/scenes/). Mitsuba's CPU backend, llvm_ad_rgb,
needs a libLLVM Dr.Jit can use: Debian 12's libLLVM 15 crashes it and its LLVM 14 is refused as too
old, so point DRJIT_LIBLLVM_PATH at a newer one (a Rust toolchain's lib/libLLVM.so.22.1-rust-*
worked); without one, --variant scalar_rgb is Mitsuba's slower scalar CPU renderer. On the GPU machine, in the bundle:
  PYTHONPATH=pydeps python3 tools/bench_efficiency.py --device gpu --variant cuda_ad_rgb \\
      --width 320 --height 240 --spp 256 --seeds 4 --ref-spp 16384 --csv efficiency-gpu.csv
The media scenes (issue 40 "Speed": pt against Mitsuba's cuda_ad_rgb volpath, Mpaths/s and relMSE x
time in one run), each at its own max depth, both Russian roulette from the third vertex (pt's
before 2026-12-06; its default is now the fifth, Mitsuba's: leave --rr-depth out to compare so):
  PYTHONPATH=pydeps python3 tools/bench_efficiency.py --device gpu --variant cuda_ad_rgb \\
      --scenes media --width 1280 --height 960 --spp 16 --seeds 4 --ref-spp 1024 \\
      --max-depth scene --rr-depth 3 --samplers pt:sobol,mitsuba:independent --csv efficiency-media-gpu.csv
(1.2 Mpixels: each reference is 1.3 G paths; the reference's own noise adds about spp/ref-spp = 1/64
of the relMSE, alike for both renderers.)
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import mitsuba_reference as ref  # noqa: E402

MITSUBA_SAMPLERS = ["independent", "stratified", "multijitter", "ldsampler"]
PT_SAMPLERS = ["sobol", "independent"]

SMALL_LIGHT_OBJ = """mtllib small-light.mtl
v -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2
v -2 0 -2\nv 2 0 -2\nv 2 3 -2\nv -2 3 -2
v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 1 -0.5\nv -0.5 1 -0.5
v -0.5 1 0.5\nv 0.5 1 0.5\nv 0.5 0 0.5\nv -0.5 0 0.5
v -0.02 2 -0.02\nv 0.02 2 -0.02\nv 0.02 2 0.02\nv -0.02 2 0.02
usemtl white\nf 1 2 3 4\nf 5 6 7 8
usemtl red\nf 12 11 10 9\nf 13 14 11 12\nf 16 15 14 13\nf 9 16 13 12\nf 10 11 14 15
usemtl lamp\nf 17 18 19 20
"""
SMALL_LIGHT_MTL = """newmtl white\nKd 0.7 0.7 0.7
newmtl red\nKd 0.6 0.1 0.08
newmtl lamp\nKd 0 0 0\nKe 2500 2400 2200
"""


def small_light_scene(folder):
    """A 4 cm square lamp 2 m over a floor, a back wall and a box: direct light from a small
    source (NEE-bound)."""
    with open(os.path.join(folder, "small-light.obj"), "w") as f:
        f.write(SMALL_LIGHT_OBJ)
    with open(os.path.join(folder, "small-light.mtl"), "w") as f:
        f.write(SMALL_LIGHT_MTL)
    path = os.path.join(folder, "small-light.json")
    with open(path, "w") as f:
        f.write('{"camera": {"eye": [0, 1.6, 4], "target": [0, 0.6, 0], "up": [0, 1, 0], "fov_y": 45},\n'
                ' "film": {"width": 160, "height": 120}, "render": {"max_depth": 8},\n'
                ' "objects": [{"obj": "small-light.obj"}]}\n')
    return path


def torus_scene(folder):
    """tools/make_bench_scenes.py's torus of about 100k triangles in its lit box."""
    import make_bench_scenes as mbs
    obj, lo, hi, count = mbs.torus_obj(100000)
    with open(os.path.join(folder, "lit-box.mtl"), "w") as f:
        f.write(mbs.MTL)
    with open(os.path.join(folder, "torus.obj"), "w") as f:
        f.write("mtllib lit-box.mtl\n" + obj)
    box, camera = mbs.box_obj(lo, hi)
    with open(os.path.join(folder, "torus-box.obj"), "w") as f:
        f.write(box)
    import json
    path = os.path.join(folder, "torus-100k.json")
    with open(path, "w") as f:
        json.dump({"camera": camera, "film": {"width": 160, "height": 120}, "render": {"max_depth": 8},
                   "objects": [{"obj": "torus.obj"}, {"obj": "torus-box.obj"}]}, f)
    return path


def media_scene(name):
    """A writer of tools/make_media_scenes.py's scene `name` into a folder (its generated mesh,
    grid and sky files included, so the scene runs from a bundle without make)."""
    def write(folder):
        import make_media_scenes
        make_media_scenes.WRITERS[name](os.path.join(folder, name))
        return os.path.join(folder, name, "scene.json")
    return write


MEDIA_SCENES = ("fog-room", "smoke", "liquid", "subsurface")

# name: a scene file under the repository, or a function writing one into a folder
SCENES = {
    "cornell": "tests/scenes/cornell/scene.json",
    "caustics": "tests/scenes/cornell-sphere/scene.json",
    "small-light": small_light_scene,
    "env-gold": "tests/scenes/envmap/scene.json",
    "rough-metals": "tests/scenes/conductors/scene.json",
    "torus-100k": torus_scene,
}
DEFAULT_SCENES = list(SCENES)
SCENES.update({name: media_scene(name) for name in MEDIA_SCENES})


def rel_mse(np, a, r):
    return float(np.mean((a - r) ** 2 / (r * r + 0.01)))


def read_exr(mi, np, path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32), dtype=np.float64)


def scene_depth(scene_path, wanted):
    """--max-depth: a number, or 'scene' for the scene file's render.max_depth."""
    if wanted != "scene":
        return int(wanted)
    return int(ref.load_scene(scene_path)[1].get("render", {}).get("max_depth", 8))


def mitsuba_scene(mi, np, scene_path, width, height, depth, sampler, spp, temp, rr_depth=None):
    path, scene = ref.load_scene(scene_path)
    scene["film"] = {"width": width, "height": height}
    scene.setdefault("render", {})["max_depth"] = depth
    d = ref.build_scene(path, scene, spp, temp, mi, np)
    d["sensor"]["sampler"] = {"type": sampler, "sample_count": spp}
    if rr_depth is not None:
        d["integrator"]["rr_depth"] = rr_depth
    return mi.load_dict(d)


def mitsuba_render(mi, dr, np, scene, spp, seed):
    start = time.perf_counter()
    img = mi.render(scene, seed=seed, spp=spp)
    dr.eval(img)
    dr.sync_thread()
    seconds = time.perf_counter() - start
    return np.array(img, dtype=np.float64), seconds


def reference(mi, dr, np, name, scene_path, args, temp):
    """The cached reference, or a Mitsuba render of --ref-spp in batches of at most 1024 spp (and
    2^25 paths)."""
    os.makedirs(args.cache, exist_ok=True)
    depth = scene_depth(scene_path, args.max_depth)
    cached = os.path.join(args.cache, f"{name}-{args.width}x{args.height}-d{depth}-{args.ref_spp}.exr")
    if os.path.exists(cached):
        return read_exr(mi, np, cached)
    # At most about 2^25 paths per launch: a GPU variant keeps every path's state at once.
    batch = min(args.ref_spp, 1024)
    while batch > 1 and batch * args.width * args.height > 1 << 25:
        batch //= 2
    scene = mitsuba_scene(mi, np, scene_path, args.width, args.height, depth, "independent", batch, temp)
    total, n = None, args.ref_spp // batch
    for k in range(n):
        img, _ = mitsuba_render(mi, dr, np, scene, batch, 100000 + k)
        total = img if total is None else total + img
    mean = total / n
    mi.Bitmap(mean.astype(np.float32)).write(cached)
    print(f"{name}: reference {args.ref_spp} spp -> {cached}", flush=True)
    return mean


def pt_render(args, scene_path, sampler, seed, out):
    cmd = [args.pt, "render", scene_path, "--width", str(args.width), "--height", str(args.height),
           "--spp", str(args.spp), "--max-depth", str(scene_depth(scene_path, args.max_depth)), "--seed", str(seed),
           "--sampler", sampler, "-o", out]
    if args.device:
        cmd += ["--device", args.device]
    run = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r" spp in ([0-9.]+) s: ([0-9.]+) Mpaths/s", run.stderr)
    if run.returncode or not m:
        raise RuntimeError(f"{' '.join(cmd)}: exit {run.returncode}: {run.stderr.strip()}")
    # Both are printed to two decimals: on a GPU the seconds (0.07) are coarse and the rate (983.04
    # Mpaths/s) fine, on a CPU the reverse; take whichever figure was rounded the less (same clock).
    seconds, rate = float(m.group(1)), float(m.group(2))
    if rate > seconds > 0 or (rate > 0 and seconds == 0):
        return args.width * args.height * args.spp / (rate * 1e6)
    return seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    built = os.path.join(ROOT, "build", "pt")
    ap.add_argument("--pt", default=built if os.path.exists(built) else os.path.join(ROOT, "bin", "pt"),
                    help="default build/pt, else bin/pt (in a bundle: tools/bundle.sh)")
    ap.add_argument("--device", help="pt's --device (cpu, gpu); default pt's choice")
    ap.add_argument("--variant", default="scalar_rgb",
                    help="llvm_ad_rgb needs a libLLVM Dr.Jit accepts (tools/bench_mitsuba.py); cuda_ad_rgb on a GPU")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--spp", type=int, default=64, help="a power of 4 suits every sampler")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--max-depth", default="64", help="a number, or 'scene': each scene's own")
    ap.add_argument("--rr-depth", type=int,
                    help="Mitsuba's rr_depth (default its own, 5, which is pt's Russian roulette too)")
    ap.add_argument("--samplers", help="only these, e.g. pt:sobol,mitsuba:independent (default all)")
    ap.add_argument("--scenes", default=",".join(DEFAULT_SCENES), help="names, or 'media' for the media scenes")
    ap.add_argument("--cache", default=os.path.join(ROOT, "bench", "results", "efficiency-references"))
    ap.add_argument("--csv", default=os.path.join(ROOT, "bench", "results", "efficiency.csv"))
    args = ap.parse_args()
    if args.scenes == "media":
        args.scenes = ",".join(MEDIA_SCENES)
    if args.max_depth != "scene":
        int(args.max_depth)  # refuses anything else with a traceback naming the value
    pt_samplers, mitsuba_samplers = PT_SAMPLERS, MITSUBA_SAMPLERS
    if args.samplers:
        chosen = [s.split(":", 1) for s in args.samplers.split(",")]
        pt_samplers = [s for r, s in chosen if r == "pt"]
        mitsuba_samplers = [s for r, s in chosen if r == "mitsuba"]
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        import bench_mitsuba
        for path in bench_mitsuba.LLVM_CANDIDATES:
            if os.path.exists(path):
                os.environ["DRJIT_LIBLLVM_PATH"] = path
                break
    import drjit as dr
    import mitsuba as mi
    import numpy as np
    variant = ref.choose_variant(mi, args.variant)
    os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
    new = not os.path.exists(args.csv)
    csv = open(args.csv, "a")
    if new:
        csv.write("scene,renderer,sampler,seed,width,height,spp,max_depth,seconds,relmse,efficiency,mpaths_per_s\n")
    summary = []
    with tempfile.TemporaryDirectory(prefix="bench-efficiency-") as temp:
        for name in args.scenes.split(","):
            source = SCENES[name]
            scene_path = source(temp) if callable(source) else os.path.join(ROOT, source)
            r = reference(mi, dr, np, name, scene_path, args, temp)
            depth = scene_depth(scene_path, args.max_depth)
            results = {}

            def record(renderer, sampler, seed, seconds, img):
                e = rel_mse(np, img, r)
                results.setdefault((renderer, sampler), []).append((e, seconds))
                mpaths = args.width * args.height * args.spp / seconds * 1e-6
                csv.write(f"{name},{renderer},{sampler},{seed},{args.width},{args.height},{args.spp},"
                          f"{depth},{seconds:.6f},{e:.6g},{1 / (e * seconds):.6g},{mpaths:.6g}\n")
                csv.flush()

            for sampler in pt_samplers:
                # warm-up: the device compiles the kernels at their first launch (PoCL), in the
                # render time pt reports
                pt_render(args, scene_path, sampler, 0, os.path.join(temp, "pt.exr"))
                for seed in range(1, args.seeds + 1):
                    out = os.path.join(temp, "pt.exr")
                    seconds = pt_render(args, scene_path, sampler, seed, out)
                    record("pt", sampler, seed, seconds, read_exr(mi, np, out))
            for sampler in mitsuba_samplers:
                scene = mitsuba_scene(mi, np, scene_path, args.width, args.height, depth,
                                      sampler, args.spp, temp, args.rr_depth)
                mitsuba_render(mi, dr, np, scene, args.spp, 0)  # warm-up (kernel compilation)
                for seed in range(1, args.seeds + 1):
                    img, seconds = mitsuba_render(mi, dr, np, scene, args.spp, seed)
                    record(f"mitsuba-{variant}", sampler, seed, seconds, img)
            summary.append((name, results))
            report(name, results, args.width * args.height * args.spp)
    print("\npt's best efficiency / Mitsuba's best (> 1: pt cleans the image sooner); "
          "pt's best speed / Mitsuba's best (Mpaths/s)")
    for name, results in summary:
        best, fastest = {}, {}
        for (renderer, sampler), v in results.items():
            eff = efficiency(v)
            side = "pt" if renderer == "pt" else "mitsuba"
            if eff > best.get(side, (0, ""))[0]:
                best[side] = (eff, sampler)
            speed = len(v) / sum(s for _, s in v)  # renders per second
            fastest[side] = max(fastest.get(side, 0), speed)
        if "pt" in best and "mitsuba" in best:
            print(f"  {name:14s} efficiency {best['pt'][0] / best['mitsuba'][0]:6.2f}  (pt {best['pt'][1]}, "
                  f"Mitsuba {best['mitsuba'][1]}); speed {fastest['pt'] / fastest['mitsuba']:6.2f}")
    return 0


def efficiency(v):
    e = sum(x for x, _ in v) / len(v)
    t = sum(s for _, s in v) / len(v)
    return 1 / (e * t)


def report(name, results, paths):
    print(f"\n{name}: {'renderer':22s} {'sampler':12s} {'relMSE':>10s} {'seconds':>9s} {'efficiency':>11s} "
          f"{'Mpaths/s':>9s}")
    for (renderer, sampler), v in results.items():
        e = sum(x for x, _ in v) / len(v)
        t = sum(s for _, s in v) / len(v)
        print(f"{'':{len(name) + 2}s}{renderer:22s} {sampler:12s} {e:10.4g} {t:9.3f} {1 / (e * t):11.4g} "
              f"{paths / t * 1e-6:9.2f}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
