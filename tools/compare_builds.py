#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""compare_builds.py PT_A PT_B [--device D] [--size WxH] [--spp N] [--scenes LIST] [--out DIR]:
renders the same scenes with two pt builds and says, scene by scene and settings variant by
variant, whether the images are bit-identical: every channel of the EXR (beauty, and the AOVs where
the variant asks for them), compared as the file's pixel chunks, which hold the
same bytes exactly when the pixels do (the header differs: render time, version). For refactorings
that promise "no behaviour change" (issue 33). Exit 0 when every pair is identical, 1 otherwise.

The scenes: every scene of scenes/ and tests/scenes/ (bench scenes that read ../shared included
when it is there) unless --scenes names others (space-separated). The variants: the default
(with every AOV), the other path kernel (PT_MEGAKERNEL flipped: the wavefront on CPUs, the
megakernel on GPUs), adaptive sampling, BSDF-only (--no-nee), the indirect clamp, and work units
(--unit-spp, the distributed path)."""
import argparse
import glob
import os
import struct
import subprocess
import sys
import tempfile

VARIANTS = {
    "default": (["--aov", "all"], {}),
    "megakernel": ([], {"PT_MEGAKERNEL": "1"}),
    "wavefront": ([], {"PT_MEGAKERNEL": "0"}),
    "adaptive": (["--noise-threshold", "0.05", "--min-spp", "4"], {}),
    "no-nee": (["--no-nee"], {}),
    "clamp": (["--clamp", "2"], {}),
    "units": (["--unit-spp", "4", "--aov", "albedo,normal,depth,spp"], {}),
}


def default_scenes(root):
    found = sorted(glob.glob(os.path.join(root, "scenes", "**", "*.json"), recursive=True))
    found += sorted(glob.glob(os.path.join(root, "tests", "scenes", "*", "scene.json")))
    shared = os.path.isdir(os.path.join(root, "..", "shared", "assets"))
    return [s for s in found if shared or not s.startswith(os.path.join(root, "scenes", "bench"))]


def exr_pixel_chunks(path):
    """The bytes after an EXR's header and offset table: its chunks (y, size, data) in order."""
    data = open(path, "rb").read()
    pos = 8  # magic and version
    while data[pos] != 0:  # attributes: name\0 type\0 size value
        pos = data.index(b"\0", pos) + 1
        pos = data.index(b"\0", pos) + 1
        (size,) = struct.unpack_from("<i", data, pos)
        pos += 4 + size
    pos += 1
    (first_chunk,) = struct.unpack_from("<Q", data, pos)
    return data[first_chunk:]


def render(pt, scene, out, args, env, common):
    cmd = [pt, "render", scene, "-o", out, "--quiet"] + common + args
    r = subprocess.run(cmd, env={**os.environ, **env}, capture_output=True, text=True)
    return r.returncode, r.stderr.strip().splitlines()[-1:] if r.returncode else []


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("pt_a")
    ap.add_argument("pt_b")
    ap.add_argument("--device", default="")
    ap.add_argument("--size", default="64x48")
    ap.add_argument("--spp", default="16")
    ap.add_argument("--scenes", default="")
    ap.add_argument("--variants", default=",".join(VARIANTS))
    ap.add_argument("--out", default="")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scenes = a.scenes.split() if a.scenes else default_scenes(root)
    w, h = a.size.split("x")
    common = ["--width", w, "--height", h, "--spp", a.spp, "--seed", "7"]
    if a.device:
        common += ["--device", a.device]
    out = a.out or tempfile.mkdtemp(prefix="compare-builds-")
    os.makedirs(out, exist_ok=True)
    same = differ = failed = both_fail = 0
    for scene in scenes:
        for v in a.variants.split(","):
            args, env = VARIANTS[v]
            paths, codes = [], []
            for side, pt in (("a", a.pt_a), ("b", a.pt_b)):
                p = os.path.join(out, f"{side}.exr")
                codes.append(render(pt, scene, p, args, env, common))
                paths.append(p)
            name = f"{os.path.relpath(scene, root)} [{v}]"
            if codes[0][0] or codes[1][0]:
                if codes[0][0] == codes[1][0]:
                    print(f"both fail  {name}: exit {codes[0][0]} {codes[0][1]}")
                    both_fail += 1
                else:
                    print(f"FAILED     {name}: exits {codes[0][0]} / {codes[1][0]} {codes[0][1]} {codes[1][1]}")
                    failed += 1
                continue
            if exr_pixel_chunks(paths[0]) == exr_pixel_chunks(paths[1]):
                print(f"identical  {name}")
                same += 1
            else:
                print(f"DIFFERENT  {name}")
                differ += 1
    print(f"compare-builds: {same} identical, {differ} different, {failed} failed"
          f"{f', {both_fail} refused by both (same exit status)' if both_fail else ''}")
    return 0 if differ == 0 and failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
