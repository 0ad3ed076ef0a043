#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Times Mitsuba 3 on a scene with per-object transforms and instancing (the forest and dragons
benchmarks of issue 18: tools/make_forest.py, tools/make_dragons.py), as tools/bench_mitsuba.py
does for plain scenes: same options, same printed line, same CSV columns, so
tools/bench-vs-mitsuba.sh runs it with MITSUBA_BENCH=tools/mitsuba_forest.py.

  .venv-mitsuba/bin/python tools/mitsuba_forest.py SCENE [--width W --height H --spp N
      --max-depth D --variant llvm_ad_rgb --reps R --csv FILE --image OUT.exr|OUT.png]

The camera, film, materials, environment or background and integrator are translated by
tools/mitsuba_reference.py's build_scene (the references' conventions). This script adds:

  ours                                    Mitsuba 3.9
  objects[].transform (ops in order)      to_world = M_n ... M_1 (p' = M p, as ours, row-major)
  the same (obj, material) named by       one 'shapegroup' of its groups' shapes, and one
  several objects                         'instance' with to_world per object: loaded once
  an object named once, or one that       the shapes themselves, with to_world (Mitsuba cannot
  emits (Mitsuba's instances cannot)      instance emitters)
  lights: directional                     'directional', direction (where it travels), irradiance
  lights: sun                             'directional' (delta): an 'angle' > 0 is dropped, with
                                          a warning (Mitsuba has no disc light of given angle)
  lights: point                           'point', position, intensity

With MITSUBA_FLATTEN=1 in the environment, shared meshes are not instanced: every object's shapes,
transformed, are joined per (mesh, group) into one 'merge' shape with one BSDF (what Mitsuba's
authors suggest where instancing is slow, mitsuba3#1017; its cuda variant did not finish a frame of
the 10^3 and 10^4 forests with shapegroups). Memory then grows with the objects.

transform_end under a shutter interval (motion blur) and spot lights are not translated: they raise an error rather than
time a different scene. Paths = width x height x spp; a warm-up render first (kernel compilation
stays out of the figures); load time is not counted.
"""
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_reference as ref  # noqa: E402
import bench_mitsuba  # noqa: E402

SCENE_KEYS = ref.SCENE_KEYS | {"lights"}
CAMERA_KEYS = ref.CAMERA_KEYS | {"shutter"}
OBJECT_KEYS = {"obj", "material", "transform", "transform_end"}


def load_scene(path):
    path, scene = ref.load_scene(path, SCENE_KEYS, CAMERA_KEYS, OBJECT_KEYS)
    shutter = scene.get("camera", {}).get("shutter", [0, 0])
    moving = shutter[0] != shutter[1]  # else pt renders every object at its transform, as here
    for i, obj in enumerate(scene.get("objects", [])):
        if "transform_end" in obj and obj["transform_end"] != obj.get("transform", []) and moving:
            raise ref.SceneError(f"{path}: objects[{i}].transform_end: motion blur is not translated "
                                 "to Mitsuba (its instances have no animated transforms)")
    return path, scene


def transform_matrix(ops, where, np):
    """The product M_n ... M_1 of the ops (the first applied first), as a 4x4 numpy array."""
    m = np.eye(4)
    for k, op in enumerate(ops):
        if not isinstance(op, dict) or len(op) != 1:
            raise ref.SceneError(f"{where}[{k}]: expected one of translate, scale, rotate, matrix")
        (name, value), = op.items()
        step = np.eye(4)
        if name == "translate":
            step[:3, 3] = [float(x) for x in value]
        elif name == "scale":
            s = [float(value)] * 3 if isinstance(value, (int, float)) else [float(x) for x in value]
            step[:3, :3] = np.diag(s)
        elif name == "rotate":
            axis = np.array(value["axis"], dtype=float)
            axis /= np.linalg.norm(axis)
            a = math.radians(float(value["angle"]))
            x, y, z = axis
            k_cross = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])  # right-handed: Rodrigues
            step[:3, :3] = np.eye(3) + math.sin(a) * k_cross + (1 - math.cos(a)) * k_cross @ k_cross
        elif name == "matrix":
            if len(value) != 16:
                raise ref.SceneError(f"{where}[{k}].matrix: expected 16 numbers, got {len(value)}")
            step = np.array(value, dtype=float).reshape(4, 4)  # row-major, column vectors
        else:
            raise ref.SceneError(f"{where}[{k}]: unknown operation '{name}'")
        m = step @ m
    return m


def light_emitter(light, where):
    kind = light.get("type")
    if kind in ("directional", "sun"):
        if kind == "sun" and float(light.get("angle", 0)) > 0:
            print(f"mitsuba_forest: {where}: the sun's angle {light['angle']} is dropped (a delta "
                  "directional light in Mitsuba)", file=sys.stderr)
        return {"type": "directional", "direction": [float(x) for x in light["direction"]],
                "irradiance": ref.rgb(light["irradiance"])}
    if kind == "point":
        return {"type": "point", "position": [float(x) for x in light["position"]],
                "intensity": ref.rgb(light["intensity"])}
    raise ref.SceneError(f"{where}: light type '{kind}' is not translated to Mitsuba")


class Meshes:
    """Each (OBJ, material override) read once: its groups as Mitsuba shape dicts."""

    def __init__(self, base, json_materials, temp_dir, mi, np):
        self.base, self.json_materials, self.temp_dir, self.mi, self.np = \
            base, json_materials, temp_dir, mi, np
        self.cache = {}
        self.has_media = False

    def shapes(self, obj_name, override):
        key = (os.path.normpath(os.path.join(self.base, obj_name)), override)
        if key not in self.cache:
            shapes = []
            for group in ref.load_obj(key[0]):
                path = os.path.join(self.temp_dir, f"mesh{len(self.cache)}_{len(shapes)}.obj")
                ref.write_group_obj(group, path)
                shape = {"type": "obj", "filename": path, "face_normals": not group.has_normals}
                name = override or group.material.name
                if name in self.json_materials:
                    shape["bsdf"], medium, emission = self.json_materials.bsdf(name)
                    if medium:
                        shape["interior"], self.has_media = medium, True
                else:
                    shape["bsdf"] = ref.bsdf_for(group.material, self.mi, self.np)
                    emission = group.material.ke if group.material.emissive else None
                if emission:
                    shape["emitter"] = {"type": "area", "radiance": ref.rgb(emission)}
                shapes.append(shape)
            self.cache[key] = (f"group{len(self.cache)}", shapes)
        return self.cache[key]


def build_scene(scene_path, scene, spp, temp_dir, mi, np):
    objects = scene.get("objects", [])
    flatten = os.environ.get("MITSUBA_FLATTEN") == "1"
    plain = {k: v for k, v in scene.items() if k not in ("objects", "lights")}
    mitsuba_scene = ref.build_scene(scene_path, plain, spp, temp_dir, mi, np)  # camera, film, sky
    base = os.path.dirname(os.path.abspath(scene_path))
    meshes = Meshes(base, ref.JsonMaterials(scene, base, mi, np), temp_dir, mi, np)
    for i, light in enumerate(scene.get("lights", [])):
        mitsuba_scene[f"light{i}"] = light_emitter(light, f"{scene_path}: lights[{i}]")
    uses = {}
    for obj in objects:
        key = (os.path.normpath(obj["obj"]), obj.get("material"))
        uses[key] = uses.get(key, 0) + 1
    defined = set()
    for i, obj in enumerate(objects):
        override = obj.get("material")
        if override is not None and override not in meshes.json_materials:
            raise ref.SceneError(f"{scene_path}: objects[{i}].material '{override}' is not a JSON material")
        group_id, shapes = meshes.shapes(obj["obj"], override)
        to_world = mi.ScalarTransform4f(transform_matrix(obj.get("transform", []),
                                                         f"{scene_path}: objects[{i}].transform", np))
        shared = uses[(os.path.normpath(obj["obj"]), override)] > 1
        if shared and flatten and not any("emitter" in s or "interior" in s for s in shapes):
            for k, s in enumerate(shapes):
                bsdf_id = f"{group_id}_bsdf{k}"
                if bsdf_id not in defined:
                    mitsuba_scene[bsdf_id] = dict(s["bsdf"], id=bsdf_id)
                    mitsuba_scene[f"{group_id}_merge{k}"] = {"type": "merge"}
                    defined.add(bsdf_id)
                merged = dict(s, to_world=to_world, bsdf={"type": "ref", "id": bsdf_id})
                mitsuba_scene[f"{group_id}_merge{k}"][f"object{i}"] = merged
        elif shared and not any("emitter" in s for s in shapes):
            if group_id not in defined:
                mitsuba_scene[group_id] = {"type": "shapegroup",
                                           **{f"s{k}": s for k, s in enumerate(shapes)}}
                defined.add(group_id)
            mitsuba_scene[f"instance{i}"] = {"type": "instance", "to_world": to_world,
                                             "shapegroup": {"type": "ref", "id": group_id}}
        else:
            for k, s in enumerate(shapes):
                mitsuba_scene[f"object{i}_{k}"] = dict(s, to_world=to_world)
    if meshes.has_media:
        mitsuba_scene["integrator"]["type"] = "volpath"
    return mitsuba_scene


def write_image(mi, img, path):
    bitmap = mi.Bitmap(img)
    if path.lower().endswith(".png"):  # tone-mapped as pt's PNG: clamp, sRGB
        bitmap = bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True)
    bitmap.write(path)


def main():
    return bench_mitsuba.main("mitsuba_forest", load_scene, build_scene, write_image)


if __name__ == "__main__":
    sys.exit(main())
