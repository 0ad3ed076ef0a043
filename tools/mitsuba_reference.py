#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Renders an independent reference image of one of our scenes with Mitsuba 3.

    mitsuba_reference.py SCENE OUT.exr [--spp N] [--batches K] [--variant V] [--stderr ERR.exr]

SCENE is a scene.json or the folder holding one. The scene is read here, its OBJ/MTL files by
tools/mitsuba_obj.py (a small reader following tinyobjloader's rules, written without looking at
the renderer's loader), and translated to a Mitsuba scene with the same conventions as the renderer
(/work/shared/DESIGN.md):

  material (MTL)                              Mitsuba
  Ke != 0                                     'area' emitter (one-sided, along the CCW normal)
                                              + the BSDF below (emitters reflect too)
  illum 4/6/7, or Ni > 1 and d < 1            dielectric, int_ior Ni (1.5 if Ni <= 1), ext_ior 1,
                                              specular_reflectance 1, specular_transmittance Tf
                                              (1 if Tf absent or zero); not wrapped: two-sided
  illum 3/5                                   twosided(conductor 'none', specular_reflectance Ks)
  anything else                               twosided(diffuse Kd * map_Kd), map_Kd sRGB-decoded,
                                              bilinear, repeat, v = 0 the bottom row
  faces without vn                            face_normals (flat shading)
  camera fov_y, look_at, aperture (diameter)  perspective/thinlens, fov_axis 'y', aperture_radius/2
  film                                        hdrfilm rgb float32, box rfilter
  background != 0                             'constant' emitter
  render.max_depth                            path integrator max_depth, hide_emitters false
                                              (volpath when the scene has media or a dielectric
                                              an absorption)
  JSON materials (replace MTL materials of    tools/mitsuba_materials.py
  the same name), textures, environment
  lights (point, spot, directional)           tools/mitsuba_lights.py
  media, medium, camera.medium, objects'      tools/mitsuba_media.py
  interior / exterior

The image is rendered in K batches with different seeds; OUT.exr is their mean, and --stderr writes
the per-pixel standard error of that mean (the batches' spread / sqrt(K)) as a half-float EXR, so
tests can tell how much of a difference is the reference's own noise.
Mitsuba is imported only when rendering: the readers work with plain Python (tools/make_test_scenes.py
uses mitsuba_obj's through this module to check the files it writes).
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
# load_obj and read_png_size are also this module's API (make_test_scenes.py, bench_mitsuba.py).
from mitsuba_obj import SceneError, load_obj, read_png_size  # noqa: E402,F401
from mitsuba_materials import JsonMaterials, environment_emitter  # noqa: E402
from mitsuba_lights import emitters as light_emitters  # noqa: E402
from mitsuba_media import Media  # noqa: E402


# ---- scene.json ----------------------------------------------------------------------------------

SCENE_KEYS = {"camera", "film", "render", "objects", "background", "materials", "textures",
              "environment", "lights", "media", "medium"}
CAMERA_KEYS = {"eye", "target", "up", "fov_y", "aperture", "focus_distance", "medium"}


def load_scene(scene_path, scene_keys=SCENE_KEYS, camera_keys=CAMERA_KEYS,
               object_keys=("obj", "material", "interior", "exterior")):
    """The scene file (or a folder's scene.json), refusing keys this translation does not know
    (tools/mitsuba_forest.py passes its wider key sets)."""
    if os.path.isdir(scene_path):
        scene_path = os.path.join(scene_path, "scene.json")
    with open(scene_path) as f:
        scene = json.load(f)
    for key, allowed in (("", scene_keys), ("camera", camera_keys),
                         ("film", {"width", "height"}), ("render", {"spp", "max_depth"})):
        section = scene if not key else scene.get(key, {})
        for k in section:
            if k not in allowed:
                raise SceneError(f"{scene_path}: unknown key '{(key + '.') if key else ''}{k}'")
    for i, obj in enumerate(scene.get("objects", [])):
        for k in obj:
            if k not in object_keys:
                raise SceneError(f"{scene_path}: unknown key 'objects[{i}].{k}'")
    return scene_path, scene


# ---- Mitsuba -------------------------------------------------------------------------------------

def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


def bsdf_for(m, mi, np):
    kind = m.kind
    if kind == "dielectric":
        tf = m.tf if any(c > 0 for c in m.tf) else [1.0, 1.0, 1.0]
        return {"type": "dielectric", "int_ior": float(m.ni if m.ni > 1 else 1.5), "ext_ior": 1.0,
                "specular_reflectance": rgb([1, 1, 1]), "specular_transmittance": rgb(tf)}
    if kind == "mirror":
        inner = {"type": "conductor", "material": "none", "specular_reflectance": rgb(m.ks)}
    elif m.map_kd:
        if not os.path.exists(m.map_kd):
            raise SceneError(f"material '{m.name}': texture {m.map_kd} not found")
        texture = {"type": "bitmap", "filter_type": "bilinear", "wrap_mode": "repeat"}
        if m.kd == [1.0, 1.0, 1.0]:
            texture["filename"] = m.map_kd  # Mitsuba decodes the sRGB itself
        else:  # Mitsuba's bitmap has no scale: multiply the decoded (linear) texels by Kd here
            bitmap = mi.Bitmap(m.map_kd).convert(mi.Bitmap.PixelFormat.RGB,
                                                 mi.Struct.Type.Float32, srgb_gamma=False)
            texels = np.array(bitmap) * np.array(m.kd, dtype=np.float32)
            texture["data"] = mi.TensorXf(texels.astype(np.float32))
            texture["raw"] = True
        inner = {"type": "diffuse", "reflectance": texture}
    else:
        inner = {"type": "diffuse", "reflectance": rgb(m.kd)}
    return {"type": "twosided", "material": inner}


def write_group_obj(group, path):
    """One triangulated OBJ per group, read by Mitsuba's own OBJ loader (which, like OBJ, puts
    v = 0 at the texture's bottom row)."""
    with open(path, "w") as f:
        f.writelines(f"v {p[0]!r} {p[1]!r} {p[2]!r}\n" for p in group.positions)
        f.writelines(f"vt {t[0]!r} {t[1]!r}\n" for t in group.texcoords)
        f.writelines(f"vn {n[0]!r} {n[1]!r} {n[2]!r}\n" for n in group.normals)
        for k, tri in enumerate(group.triangles):
            corners = []
            for j in range(3):
                s = str(tri[j] + 1)
                if group.has_uv or group.has_normals:
                    s += "/" + (str(group.tri_uv[k][j] + 1) if group.has_uv else "")
                if group.has_normals:
                    s += "/" + str(group.tri_normals[k][j] + 1)
                corners.append(s)
            f.write("f " + " ".join(corners) + "\n")


def build_scene(scene_path, scene, spp, temp_dir, mi, np):
    cam = scene.get("camera", {})
    film = scene.get("film", {})
    eye = cam.get("eye", [0, 0, 0])
    target = cam.get("target", [0, 0, -1])
    aperture = float(cam.get("aperture", 0.0))
    sensor = {
        "type": "thinlens" if aperture > 0 else "perspective",
        "fov": float(cam.get("fov_y", 40.0)), "fov_axis": "y",
        "to_world": mi.ScalarTransform4f().look_at(origin=eye, target=target,
                                                   up=cam.get("up", [0, 1, 0])),
        "sampler": {"type": "independent", "sample_count": spp},
        "film": {"type": "hdrfilm", "width": int(film.get("width", 128)),
                 "height": int(film.get("height", 128)), "rfilter": {"type": "box"},
                 "pixel_format": "rgb", "component_format": "float32", "sample_border": False},
    }
    if aperture > 0:
        sensor["aperture_radius"] = aperture / 2  # our JSON has the lens diameter
        sensor["focus_distance"] = float(cam.get("focus_distance",
                                                 math.dist(eye, target)))
    base = os.path.dirname(os.path.abspath(scene_path))
    media = Media(scene, base)
    # The media first: the sensor and the shapes refer to them by id.
    mitsuba_scene = {"type": "scene", **media.plugins(), "sensor": sensor}
    if media.sensor_medium():
        sensor["medium"] = media.sensor_medium()
    mitsuba_scene.update(light_emitters(scene, mi))
    json_materials = JsonMaterials(scene, base, mi, np)
    if "environment" in scene:
        mitsuba_scene["environment"] = environment_emitter(scene["environment"], base, mi, np)
    else:
        background = scene.get("background", [0, 0, 0])
        if any(c > 0 for c in background):
            mitsuba_scene["background"] = {"type": "constant", "radiance": rgb(background)}
    count, has_media = 0, bool(media)
    for index, obj in enumerate(scene.get("objects", [])):
        override = obj.get("material")
        if override is not None and override not in json_materials:
            raise SceneError(f"{scene_path}: objects[].material '{override}' is not a JSON material")
        for group in load_obj(os.path.join(base, obj["obj"])):
            path = os.path.join(temp_dir, f"group{count}.obj")
            write_group_obj(group, path)
            shape = {"type": "obj", "filename": path, "face_normals": not group.has_normals}
            name = override or group.material.name
            if name in json_materials:  # a JSON material replaces the MTL one of the same name
                shape["bsdf"], medium, emission = json_materials.bsdf(name)
                has_media |= medium is not None
                shape.update(media.shape_media(obj, f"objects[{index}]", medium))
            else:
                shape.update(media.shape_media(obj, f"objects[{index}]"))
                shape["bsdf"] = bsdf_for(group.material, mi, np)
                medium, emission = None, group.material.ke if group.material.emissive else None
            if emission:
                shape["emitter"] = {"type": "area", "radiance": rgb(emission)}
            mitsuba_scene[f"shape{count}_{name}"] = shape
            count += 1
    # volpath is Mitsuba's path tracer with media; without any it renders what 'path' does.
    mitsuba_scene["integrator"] = {"type": "volpath" if has_media else "path",
                                   "max_depth": int(scene.get("render", {}).get("max_depth", 8)),
                                   "hide_emitters": False}
    return mitsuba_scene


def choose_variant(mi, wanted):
    """Takes the first variant that works; llvm needs a libLLVM Dr.Jit accepts (Debian 12's 15
    crashes, libllvm19 works through DRJIT_LIBLLVM_PATH)."""
    for v in wanted.split(","):
        try:
            mi.set_variant(v)
            return v
        except Exception as e:  # noqa: BLE001  (any failure: try the next variant)
            print(f"mitsuba_reference: variant {v} unavailable ({e}); trying the next", file=sys.stderr)
    raise SceneError(f"none of the variants {wanted} works")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--spp", type=int, default=4096, help="total samples per pixel")
    ap.add_argument("--batches", type=int, default=16, help="independent batches (for --stderr)")
    ap.add_argument("--variant", default="scalar_rgb",
                    help="Mitsuba variant(s), comma-separated, first that works")
    ap.add_argument("--stderr", help="also write the per-pixel standard error of the mean here")
    ap.add_argument("--seed", type=int, default=0, help="seed of the first batch")
    args = ap.parse_args()
    if args.spp % args.batches:
        ap.error("--spp must be a multiple of --batches")

    import mitsuba as mi
    import numpy as np
    variant = choose_variant(mi, args.variant)
    try:
        scene_path, scene = load_scene(args.scene)
        with tempfile.TemporaryDirectory(prefix="mitsuba-ref-") as temp_dir:
            per_batch = args.spp // args.batches
            scene_obj = mi.load_dict(build_scene(scene_path, scene, per_batch, temp_dir, mi, np))
    except (SceneError, OSError, json.JSONDecodeError) as e:
        print(f"mitsuba_reference: {e}", file=sys.stderr)
        return 1

    start = time.time()
    total = total_sq = None
    for b in range(args.batches):
        img = np.array(mi.render(scene_obj, seed=args.seed + b, spp=per_batch), dtype=np.float64)
        total = img if total is None else total + img
        total_sq = img * img if total_sq is None else total_sq + img * img
    seconds = time.time() - start
    mean = total / args.batches
    if args.batches > 1:
        var = np.maximum(total_sq / args.batches - mean * mean, 0) * args.batches / (args.batches - 1)
        stderr = np.sqrt(var / args.batches)
    else:
        stderr = np.zeros_like(mean)
    if not np.all(np.isfinite(mean)):
        print("mitsuba_reference: the render has NaN/Inf pixels", file=sys.stderr)
        return 1

    mi.Bitmap(mean.astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(args.out)
    if args.stderr:
        mi.Bitmap(stderr.astype(np.float16), pixel_format=mi.Bitmap.PixelFormat.RGB).write(args.stderr)
    means = mean.reshape(-1, 3).mean(axis=0)
    noisy = stderr[stderr > 0]  # pixels that only see the background have none
    print(f"{args.out}: mitsuba {mi.__version__} {variant}, {args.spp} spp in {args.batches} batches, "
          f"{seconds:.1f} s; mean RGB {means[0]:.5f} {means[1]:.5f} {means[2]:.5f}; "
          f"std error of the mean: median {np.median(noisy) if noisy.size else 0:.5f} over the "
          f"{100 * noisy.size / stderr.size:.0f} % of values that vary, max {stderr.max():.5f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
