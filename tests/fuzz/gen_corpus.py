#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""gen_corpus.py OUT [--seeds DIR]: writes the malformed-input corpus into OUT/cases/ (one folder
per case); with --seeds, also the seed inputs of the libFuzzer targets (DIR/scene, DIR/obj,
DIR/texture, DIR/ply, DIR/gltf, DIR/checkpoint, DIR/pbrt: the corpus's scene files, OBJ+MTL pairs, images,
PLY files, GLB files and checkpoints).

Each case folder holds its input files and case.json:
  args    the pt command line (after the binary); run with the case folder as working directory.
          "{repo}" is replaced by the repository root at replay time.
  env     variables set for the run (on top of the replay's own); a value of null unsets one.
  expect  "ok" (exit 0), "error" (non-zero exit and one "pt: ..." line last on stderr) or "any"
          (either of those); never a signal, a sanitizer report, a hang or a silent failure.
  needle  optional text the error line must contain (the file or value it names).
  setup   optional shell run in the case folder before pt ($PT_FUZZ_CACHE: a warm kernel cache).
  known   a known failure owned elsewhere (reported, not counted as failed): remove once fixed.
  timeout seconds instead of the replay's default (more for a cold kernel compile, less for a
          known hang).
Deterministic: the same corpus every run (seeded), so a failure names a case that stays put.
The cases come from one module per input kind: corpus_scene.py, corpus_obj.py (OBJ and MTL),
corpus_texture.py, corpus_materials.py (materials v2: JSON blocks and MTL statements),
corpus_transform.py (objects' transforms, the camera's shutter),
corpus_ply.py (PLY files, and scenes naming them with "ply"), corpus_gltf.py (glTF and GLB files,
and scenes naming them with "gltf"), corpus_gltf_v2.py, corpus_ply_v2.py and corpus_scene_v2.py
(hostile cases for the v2 readers), corpus_checkpoint.py (checkpoints read by --resume),
corpus_cli.py (outputs, command line, environment), corpus_pbrt.py (pbrt-v4 scenes),
corpus_mitsuba.py (Mitsuba 3 XML scenes),
corpus_collada.py (COLLADA, the Assimp formats, Draco glTF), corpus_media.py (media: the "media"
block, interiors, subsurface, .vol grids); corpus_cases.py holds the
list they append to.
"""
import json
import os
import random
import shutil
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
from corpus_cases import cases  # noqa: E402
from corpus_checkpoint import checkpoint_cases, checkpoint_seeds  # noqa: E402
from corpus_cli import cli_cases, env_cases  # noqa: E402
from corpus_collada import collada_cases  # noqa: E402
from corpus_gltf import gltf_cases  # noqa: E402
from corpus_gltf_v2 import gltf_v2_cases  # noqa: E402
from corpus_materials import material_cases  # noqa: E402
from corpus_media import media_cases, mitsuba_media_cases  # noqa: E402
from corpus_mitsuba import mitsuba_cases  # noqa: E402
from corpus_obj import mtl_cases, obj_cases  # noqa: E402
from corpus_pbrt import pbrt_cases  # noqa: E402
from corpus_ply import ply_cases  # noqa: E402
from corpus_ply_v2 import ply_v2_cases  # noqa: E402
from corpus_scene import json_cases  # noqa: E402
from corpus_scene_v2 import scene_v2_cases  # noqa: E402
from corpus_texture import environment_map_cases, texture_cases  # noqa: E402
from corpus_transform import transform_cases  # noqa: E402


def as_bytes(content):
    return content.encode("utf-8", "surrogateescape") if isinstance(content, str) else content


def write_seeds(folder):
    for target in ("scene", "obj", "texture", "ply", "gltf", "checkpoint", "pbrt", "mitsuba", "collada", "assimp"):
        os.makedirs(os.path.join(folder, target), exist_ok=True)
    for i, c in enumerate(cases):
        files, seed = c["files"], None
        if c["name"].startswith("json-") and "scene.json" in files:
            target, seed = "scene", as_bytes(files["scene.json"])
        elif c["name"].startswith(("obj-", "mtl-")) and "x.obj" in files:
            target, seed = "obj", as_bytes(files["x.obj"])
            if "m.mtl" in files:
                seed += b"\n#MTL\n" + as_bytes(files["m.mtl"])
        elif c["name"].startswith("ply-") and "x.ply" in files:
            target, seed = "ply", as_bytes(files["x.ply"])
        elif c["name"].startswith("gltf-") and "x.glb" in files:
            target, seed = "gltf", as_bytes(files["x.glb"])
        elif c["name"].startswith("pbrt-") and "scene.pbrt" in c["files"]:
            target, seed = "pbrt", as_bytes(files["scene.pbrt"])
        elif c["name"].startswith("mitsuba-") and "scene.xml" in files:
            target, seed = "mitsuba", as_bytes(files["scene.xml"])
        elif c["name"].startswith("dae-") and "x.dae" in files:
            target, seed = "collada", as_bytes(files["x.dae"])
        elif c["name"].startswith(("stl-", "off-", "fbx-", "3ds-", "x3d-")):  # fuzz_assimp.c: format byte
            kind = ("stl-", "off-", "fbx-", "3ds-", "x3d-").index(c["name"][:4])
            target, seed = "assimp", bytes([kind]) + as_bytes(next(iter(files.values())))
        elif c["name"].startswith("tex-"):
            images = [n for n in files if n.startswith("t.")]
            if images:
                target, seed = "texture", as_bytes(files[images[0]])
        if seed is not None and len(seed) < 1 << 20:
            with open(os.path.join(folder, target, "seed-%03d" % i), "wb") as f:
                f.write(seed)
    for i, seed in enumerate(checkpoint_seeds()):
        with open(os.path.join(folder, "checkpoint", "seed-%03d" % i), "wb") as f:
            f.write(seed)


def main():
    out = sys.argv[1]
    rng = random.Random(20261201)
    json_cases(rng)
    obj_cases(rng)
    mtl_cases(rng)
    texture_cases(rng)
    cli_cases()
    env_cases()
    environment_map_cases()
    material_cases()
    transform_cases()
    ply_cases()
    gltf_cases(random.Random(20261202))
    checkpoint_cases()
    pbrt_cases(random.Random(20261206))  # after the others: earlier cases keep their numbers
    mitsuba_cases(random.Random(20261207))  # after: the cases above keep their numbers
    collada_cases(random.Random(20261208))
    gltf_v2_cases()  # issue 42's hostile cases for the v2 readers
    ply_v2_cases()
    scene_v2_cases()
    media_cases()  # issue 40: media, last so that the cases above keep their numbers
    mitsuba_media_cases()
    root = os.path.join(out, "cases")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    names = set()
    for i, c in enumerate(cases):
        name = "%03d-%s" % (i, "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in c["name"]))
        assert c["name"] not in names, c["name"]
        names.add(c["name"])
        folder = os.path.join(root, name[:120])
        os.makedirs(folder)
        for fname, content in c["files"].items():
            data = as_bytes(content)
            with open(os.path.join(folder, fname), "wb") as f:
                f.write(data)
        meta = {k: c[k] for k in ("args", "env", "expect", "needle", "setup", "known", "timeout")}
        with open(os.path.join(folder, "case.json"), "w") as f:
            json.dump(meta, f)
    print("gen_corpus: %d cases in %s" % (len(cases), root))
    if len(sys.argv) > 3 and sys.argv[2] == "--seeds":
        write_seeds(sys.argv[3])


if __name__ == "__main__":
    main()
