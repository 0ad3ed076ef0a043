#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes one of our test scenes as a Mitsuba 3 XML file: the very scene tools/mitsuba_reference.py
hands Mitsuba to render tests/references/<scene>.exr, serialised instead of rendered.

    mitsuba_xml.py SCENE OUT_FOLDER [SCENE OUT_FOLDER ...]

OUT_FOLDER gets scene.xml, the per-material OBJ groups it names and copies of the textures (a
Mitsuba file's paths stay inside its folder). tests/test_reference.c renders these files with pt's
Mitsuba importer and compares them with the same references, so the importer is checked against
Mitsuba itself. Runs without Mitsuba: a scene that needs Mitsuba's Python objects (an in-memory
bitmap: a Kd-scaled map_Kd, an environment map) is refused with SceneError.
"""
import os
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
from mitsuba_obj import SceneError  # noqa: E402
from mitsuba_reference import build_scene, load_scene  # noqa: E402


class Transform:
    """Mitsuba's ScalarTransform4f as the list of XML operations it was made of."""

    def __init__(self, ops=()):
        self.ops = list(ops)

    def look_at(self, origin, target, up):
        return Transform(self.ops + [("lookat", {"origin": origin, "target": target, "up": up})])

    def rotate(self, axis, angle):
        return Transform(self.ops + [("rotate", {"x": axis[0], "y": axis[1], "z": axis[2], "angle": angle})])


class NoMitsuba:
    ScalarTransform4f = Transform

    def __getattr__(self, name):
        raise SceneError(f"needs Mitsuba's {name} (an in-memory bitmap): not written as XML")


TAGS = {"bitmap": "texture", "area": "emitter", "constant": "emitter", "envmap": "emitter",
        "obj": "shape", "hdrfilm": "film", "box": "rfilter", "independent": "sampler",
        "path": "integrator", "volpath": "integrator", "homogeneous": "medium",
        "perspective": "sensor", "thinlens": "sensor",
        "heterogeneous": "medium", "gridvolume": "volume", "hg": "phase",
        "point": "emitter", "spot": "emitter", "directional": "emitter"}


def number(v):
    return repr(float(v))


def vector(v):
    return ", ".join(number(x) for x in v)


class Writer:
    def __init__(self, folder):
        self.folder, self.lines = folder, []

    def local(self, path):
        """A file the scene names, copied beside the XML (if not there already)."""
        name = os.path.basename(path)
        target = os.path.join(self.folder, name)
        if os.path.abspath(path) != os.path.abspath(target):
            shutil.copyfile(path, target)
        return name

    def element(self, tag, d, depth, name=None, id=None):
        pad = "    " * depth
        head = f'{pad}<{tag} type="{d["type"]}"' + (f' name="{name}"' if name else "") + (
            f' id="{id}"' if id else "")
        body = []
        for key, v in d.items():
            if key == "type":
                continue
            inner = "    " * (depth + 1)
            if isinstance(v, bool):
                body.append(f'{inner}<boolean name="{key}" value="{"true" if v else "false"}"/>')
            elif isinstance(v, int):
                body.append(f'{inner}<integer name="{key}" value="{v}"/>')
            elif isinstance(v, float):
                body.append(f'{inner}<float name="{key}" value="{number(v)}"/>')
            elif isinstance(v, str):
                value = self.local(v) if key == "filename" else v
                body.append(f'{inner}<string name="{key}" value="{value}"/>')
            elif isinstance(v, Transform):
                body.append(f'{inner}<transform name="{key}">')
                for op, args in v.ops:
                    attrs = " ".join(f'{k}="{vector(a) if isinstance(a, (list, tuple)) else number(a)}"'
                                     for k, a in args.items())
                    body.append(f"{inner}    <{op} {attrs}/>")
                body.append(f"{inner}</transform>")
            elif isinstance(v, list) and len(v) == 3:  # a point light's position, a direction
                tag_of = "point" if key == "position" else "vector"
                body.append(f'{inner}<{tag_of} name="{key}" x="{number(v[0])}" y="{number(v[1])}" '
                            f'z="{number(v[2])}"/>')
            elif isinstance(v, dict) and v.get("type") == "ref":  # a medium defined at the top
                body.append(f'{inner}<ref name="{key}" id="{v["id"]}"/>')
            elif isinstance(v, dict) and v.get("type") == "rgb":
                body.append(f'{inner}<rgb name="{key}" value="{vector(v["value"])}"/>')
            elif isinstance(v, dict):
                tag_of = TAGS.get(v["type"], "bsdf")
                body.extend(self.element(tag_of, v, depth + 1, name=key))
            else:
                raise SceneError(f"{key}: {type(v).__name__} is not written as XML")
        if not body:
            return [head + "/>"]
        return [head + ">"] + body + [f"{pad}</{tag}>"]


def write(scene_dir, folder):
    os.makedirs(folder, exist_ok=True)
    scene_path, scene = load_scene(scene_dir)
    spp = int(scene.get("render", {}).get("spp", 64))
    with tempfile.TemporaryDirectory(prefix="mitsuba-xml-") as temp:
        d = build_scene(scene_path, scene, spp, temp, NoMitsuba(), None)
        w = Writer(folder)
        lines = ['<scene version="3.0.0">']
        for key, v in d.items():
            if key != "type":
                lines.extend(w.element(TAGS.get(v["type"], "bsdf"), v, 1, id=key))
        lines.append("</scene>")
    with open(os.path.join(folder, "scene.xml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    args = sys.argv[1:]
    if not args or len(args) % 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        for i in range(0, len(args), 2):
            write(args[i], args[i + 1])
    except (SceneError, OSError) as e:
        print(f"mitsuba_xml: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
