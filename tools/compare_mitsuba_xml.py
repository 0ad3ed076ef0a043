#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Renders a Mitsuba 3 XML scene with Mitsuba and with pt's importer and compares the images:
the check of the importer's conventions (camera handedness, fov axes, envmap orientation, the
BSDF mapping) on scenes that have no committed reference.

    compare_mitsuba_xml.py SCENE.xml [--pt build/pt] [--spp N] [-D NAME=VALUE ...]

Prints each image's per-channel mean, the mean absolute difference and the relative one
(sum |a - b| / sum a); writes SCENE.mitsuba.exr and SCENE.pt.exr beside the scene. Needs the
virtualenv of tools/mitsuba-venv.sh (run it with .venv-mitsuba/bin/python).
"""
import argparse
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--pt", default="build/pt")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("-D", action="append", default=[], help="NAME=VALUE, for both renderers")
    args = ap.parse_args()
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    params = dict(d.split("=", 1) for d in args.D)
    stem = os.path.splitext(args.scene)[0]
    scene = mi.load_file(args.scene, **params)
    ours_mitsuba = np.array(mi.render(scene, spp=args.spp), dtype=np.float64)[:, :, :3]
    mi.Bitmap(ours_mitsuba.astype(np.float32)).write(stem + ".mitsuba.exr")
    command = [args.pt, "render", args.scene, "--spp", str(args.spp), "--device", "cpu", "--quiet",
               "-o", stem + ".pt.exr"] + [x for d in args.D for x in ("-D", d)]
    if subprocess.run(command).returncode:
        return 1
    ours_pt = np.array(mi.Bitmap(stem + ".pt.exr").convert(mi.Bitmap.PixelFormat.RGB,
                                                            mi.Struct.Type.Float32), dtype=np.float64)
    if ours_pt.shape != ours_mitsuba.shape:
        print(f"sizes differ: pt {ours_pt.shape}, Mitsuba {ours_mitsuba.shape}")
        return 1
    diff = np.abs(ours_pt - ours_mitsuba)
    print(f"{args.scene}: mean RGB Mitsuba {ours_mitsuba.reshape(-1, 3).mean(0).round(4)}, "
          f"pt {ours_pt.reshape(-1, 3).mean(0).round(4)}; mean |difference| {diff.mean():.4f}, "
          f"relative {diff.sum() / max(np.abs(ours_mitsuba).sum(), 1e-12):.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
