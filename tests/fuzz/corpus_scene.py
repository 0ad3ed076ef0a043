# SPDX-License-Identifier: MIT
"""Cases for the JSON scene reader: truncations, byte flips, wrong types, unknown keys, nesting,
special files as objects.
"""
import json

from corpus_black_holes import black_holes_cases
from corpus_cases import BASE_SCENE, TINY, TRIANGLE, case, cases


def scene_case(name, text, expect="any", needle=None, extra_files=None, args_extra=None):
    files = {"tri.obj": TRIANGLE, "scene.json": text}
    files.update(extra_files or {})
    case("json-" + name, files, ["render", "scene.json"] + TINY + (args_extra or []), expect,
         needle=needle)


def json_cases(rng):
    base = json.dumps(BASE_SCENE, indent=1)
    scene_case("valid", base, "ok")
    for i, cut in enumerate(range(1, len(base), max(1, len(base) // 20))):
        scene_case("truncated-%02d" % i, base[:cut], "error", needle="scene.json")
    for i in range(15):
        b = bytearray(base.encode())
        for _ in range(rng.randint(1, 4)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        scene_case("byteflip-%02d" % i, bytes(b))
    for name, text in [("empty", ""), ("blank", "  \n\t\n"), ("null", "null"), ("array", "[]"),
                       ("number", "42"), ("string", '"scene"'), ("nul-byte", base[:20] + "\0" + base[20:]),
                       ("bom", "\ufeff" + base), ("trailing-garbage", base + "}}"),
                       ("trailing-comma", base[:-2] + ",\n}"), ("comment", "// c\n" + base),
                       ("single-quotes", base.replace('"', "'")), ("two-objects", base + base),
                       ("unclosed-string", '{"objects": [{"obj": "tri.obj}]}'),
                       ("nan-literal", base.replace('"fov_y": 40', '"fov_y": NaN')),
                       ("inf-literal", base.replace('"fov_y": 40', '"fov_y": Infinity')),
                       ("binary", bytes(range(256)) * 4)]:
        scene_case(name, text)
    values = {"null": None, "true": True, "string": "x", "empty-array": [], "object": {},
              "four": [1, 2, 3, 4], "zero": 0, "minus-one": -1, "huge": 1e308,
              "int-overflow": 2147483648, "tiny": 5e-324, "huge-string": "s" * 100000}
    paths = ["camera", "camera.eye", "camera.target", "camera.up", "camera.fov_y", "camera.aperture",
             "camera.focus_distance", "film", "film.width", "film.height", "render", "render.spp",
             "render.max_depth", "render.sampler", "background", "objects", "objects.0", "objects.0.obj"]
    for path in paths:
        for vname, value in values.items():
            scene = json.loads(json.dumps(BASE_SCENE))
            node, keys = scene, path.split(".")
            for k in keys[:-1]:
                node = node[int(k)] if k.isdigit() else node[k]
            last = keys[-1]
            if last.isdigit():
                node[int(last)] = value
            else:
                node[last] = value
            scene_case("type-%s-%s" % (path, vname), json.dumps(scene))
    for where in ["", "camera", "film", "render", "objects.0"]:
        scene = json.loads(json.dumps(BASE_SCENE))
        node = scene
        for k in filter(None, where.split(".")):
            node = node[int(k)] if k.isdigit() else node[k]
        node["bogus_key"] = 1
        scene_case("unknown-key-%s" % (where or "root"), json.dumps(scene), "error",
                   needle="bogus_key")
    # The message gives the unknown key's own line: the path is followed member by member
    # (objects[2], not the first object with such a key), past strings holding quotes and braces.
    lines = ['{', ' "objects": [', '  {"obj": "tri.obj", "smooth": true},',
             '  {"obj": "tri.obj", "material": "a \\"{[b"},', '  {"obj": "tri.obj",',
             '   "bogus_key": 1}', ' ],', ' "materials": {"a \\"{[b": {"type": "diffuse"}}', '}']
    scene_case("unknown-key-line", "\n".join(lines) + "\n", "error",
               needle="scene.json:6: objects[2].bogus_key: unknown key (accepted: ")
    scene_case("deep-array", '{"objects": ' + "[" * 20000 + "]" * 20000 + "}", "error")
    scene_case("deep-object", '{"camera": ' + '{"a":' * 5000 + "1" + "}" * 5000 + "}", "error")
    long_name = "d" * 5000 + ".obj"
    scene = json.loads(json.dumps(BASE_SCENE))
    scene["objects"] = [{"obj": long_name}]
    scene_case("long-obj-path", json.dumps(scene), "error")
    scene["objects"] = [{"obj": "tri.obj"}] * 2000
    scene_case("many-objects", json.dumps(scene), "ok")
    scene["objects"] = []
    scene_case("no-objects", json.dumps(scene), "ok")  # the sky alone (issue 36)
    for special in ["/dev/zero", "/dev/null", "/", ".", "fifo.obj", "/proc/self/mem", "tri.obj/x"]:
        scene = json.loads(json.dumps(BASE_SCENE))
        scene["objects"] = [{"obj": special}]
        setup = "mkfifo fifo.obj" if special == "fifo.obj" else None
        cases.append(dict(name="json-object-%s" % special.strip("/").replace("/", "-") or "root",
                          files={"tri.obj": TRIANGLE, "scene.json": json.dumps(scene)},
                          args=["render", "scene.json"] + TINY, expect="error", env={},
                          needle=None, setup=setup, known=None, timeout=None))
    case("json-scene-is-fifo", {}, ["render", "scene.json"] + TINY, "error", setup="mkfifo scene.json",
         timeout=60)
    case("json-scene-is-dev-zero", {}, ["render", "/dev/zero"] + TINY, "error")
    case("json-huge-file", {"tri.obj": TRIANGLE}, ["render", "scene.json"] + TINY, "error",
         setup="truncate -s 70M scene.json")
    # render.denoise: a boolean; other types are one-line errors (true would load OIDN: not here).
    for vname, value in [("string", "yes"), ("number", 1), ("null", None), ("array", [True])]:
        scene = json.loads(json.dumps(BASE_SCENE))
        scene["render"]["denoise"] = value
        scene_case("denoise-%s" % vname, json.dumps(scene), "error", needle="render.denoise")
    lights_cases()
    black_holes_cases(scene_case)


def lights_cases():
    """The "lights" array: each type valid, then bad values that must be one-line errors."""
    good = {"point": {"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
            "spot": {"type": "spot", "position": [0, 1, 0], "intensity": 2, "direction": [0, -1, 0],
                     "cone_angle": 40, "falloff_angle": 20},
            "directional": {"type": "directional", "direction": [1, -1, 0], "irradiance": [1, 1, 1]},
            "sun": {"type": "sun", "direction": [0, -1, 0], "irradiance": 3, "angle": 0.5}}
    for name, light in good.items():
        scene = json.loads(json.dumps(BASE_SCENE))
        scene["lights"] = [light]
        scene_case("lights-valid-%s" % name, json.dumps(scene), "ok")
    bad = [("zero-direction", "directional", "direction", [0, 0, 0]),
           ("falloff-over-cone", "spot", "falloff_angle", 60),
           ("negative-intensity", "point", "intensity", [1, -1, 1]),
           ("negative-irradiance", "sun", "irradiance", -1),
           ("huge-angle", "sun", "angle", 1e30),
           ("string-type", "point", "type", 3),
           ("unknown-type", "point", "type", "area"),
           ("extra-key", "point", "angle", 1)]
    for name, kind, key, value in bad:
        scene = json.loads(json.dumps(BASE_SCENE))
        light = dict(good[kind])
        light[key] = value
        scene["lights"] = [light]
        scene_case("lights-%s" % name, json.dumps(scene), "error", needle="lights[0]")
    scene = json.loads(json.dumps(BASE_SCENE))
    for name, value in [("missing-position", {"type": "point", "intensity": 1}),
                        ("not-an-object", 7), ("not-an-array", None)]:
        scene["lights"] = [value] if name != "not-an-array" else {"type": "point"}
        scene_case("lights-%s" % name, json.dumps(scene), "error", needle="lights")
    scene["lights"] = [good["sun"]] * 3000
    scene_case("lights-many", json.dumps(scene), "ok")
