#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Times Mitsuba 3 on one of our scenes: the yardstick for `pt bench` on the same machine.

The scene is converted as tools/mitsuba_reference.py does (same camera, film, materials, path
integrator with our max depth; Mitsuba's own Russian roulette starts later than ours, at depth 5,
so it traces at least as many rays). After a warm-up render (Dr.Jit compiles and caches its
kernels), each timed render is one mi.render of the whole film; paths = width x height x spp.
Prints one line per render and appends rows to --csv.

  .venv-mitsuba/bin/python tools/bench_mitsuba.py SCENE [--width W --height H --spp N
      --max-depth D --variant llvm_ad_rgb --reps R --csv FILE]

llvm_ad_rgb (Mitsuba's vectorised CPU backend) needs a libLLVM that Dr.Jit accepts: Debian 12's
libLLVM 15 crashes, Debian's libllvm19 works; DRJIT_LIBLLVM_PATH is set to it when found.
"""
import argparse
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_reference as ref  # noqa: E402

LLVM_CANDIDATES = ["/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1",
                   "/usr/lib/llvm-19/lib/libLLVM.so"]


def write_exr(mi, img, path):
    mi.Bitmap(img).write(path)


def main(name="bench_mitsuba", load_scene=None, build_scene=None, write_image=write_exr):
    """Times Mitsuba on a pt scene. tools/mitsuba_forest.py passes its own scene loader and builder
    (transforms, instances, analytic lights) and image writer; the rest is shared."""
    load_scene = load_scene or ref.load_scene
    build_scene = build_scene or ref.build_scene
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--spp", type=int, default=8)
    ap.add_argument("--max-depth", type=int)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--csv")
    ap.add_argument("--rr-depth", type=int,
                    help="Mitsuba's rr_depth (default its own, 5, which is also pt's: Russian roulette "
                    "from the fifth vertex, so that both trace the same number of rays per path)")
    ap.add_argument("--image", help="also write the last timed render here (EXR; mitsuba_forest: "
                    "or PNG in sRGB), to compare with pt's")
    args = ap.parse_args()
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        for path in LLVM_CANDIDATES:
            if os.path.exists(path):
                os.environ["DRJIT_LIBLLVM_PATH"] = path
                break

    import drjit as dr
    import mitsuba as mi
    import numpy as np
    try:
        variant = ref.choose_variant(mi, args.variant)
    except ref.SceneError as e:
        print(f"{name}: {e} (llvm_ad_rgb needs Debian's libllvm19: apt install libllvm19, "
              "or DRJIT_LIBLLVM_PATH pointing at a libLLVM that Dr.Jit accepts)", file=sys.stderr)
        return 1
    try:
        scene_path, scene = load_scene(args.scene)
        film = scene.setdefault("film", {})
        if args.width:
            film["width"] = args.width
        if args.height:
            film["height"] = args.height
        if args.max_depth:
            scene.setdefault("render", {})["max_depth"] = args.max_depth
        width, height = int(film.get("width", 128)), int(film.get("height", 128))
        depth = int(scene.get("render", {}).get("max_depth", 8))
        start = time.perf_counter()
        with tempfile.TemporaryDirectory(prefix=f"{name}-") as temp_dir:
            scene_dict = build_scene(scene_path, scene, args.spp, temp_dir, mi, np)
            if args.rr_depth is not None:
                scene_dict["integrator"]["rr_depth"] = args.rr_depth
            scene_obj = mi.load_dict(scene_dict)
        load_seconds = time.perf_counter() - start
    except (ref.SceneError, OSError, ValueError, KeyError, TypeError) as e:
        print(f"{name}: {e}", file=sys.stderr)
        return 1
    print(f"{name}: {args.scene}: {len(scene.get('objects', []))} objects loaded in "
          f"{load_seconds:.2f} s (not counted)")

    def render(seed):
        img = mi.render(scene_obj, seed=seed, spp=args.spp)
        dr.eval(img)
        dr.sync_thread()
        return img

    render(0)  # warm-up: kernel compilation stays out of the figures
    paths = width * height * args.spp
    rows = []
    for r in range(args.reps):
        start = time.perf_counter()
        img = render(r + 1)
        seconds = time.perf_counter() - start
        rows.append(seconds)
        print(f"mitsuba {mi.__version__} {variant}: {args.scene} {width}x{height} {args.spp} spp "
              f"depth {depth}: {seconds * 1e3:.1f} ms, {paths / seconds * 1e-6:.2f} Mpaths/s")
    if args.image:
        write_image(mi, img, args.image)
    if args.csv:
        new = not os.path.exists(args.csv) or os.path.getsize(args.csv) == 0
        with open(args.csv, "a") as f:
            if new:
                f.write("renderer,variant,scene,width,height,spp,max_depth,seconds,mpaths_per_s\n")
            for seconds in rows:
                f.write(f"mitsuba-{mi.__version__},{variant},{args.scene},{width},{height},{args.spp},"
                        f"{depth},{seconds:.6f},{paths / seconds * 1e-6:.3f}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
