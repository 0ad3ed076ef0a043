# SPDX-License-Identifier: MIT
"""Cases for the scene graph's transforms: objects' "transform" and "transform_end" and the
camera's "shutter". Valid scenes use every operation (and a mirror, and motion); every bad value is
a one-line error naming objects[i] and the key.
"""
import json

from corpus_cases import BASE_SCENE, TINY, TRIANGLE, case

ROTATE = {"rotate": {"axis": [0, 1, 0], "angle": 30}}
EVERY_OP = [{"scale": 0.5}, {"scale": [1, -1, 1]}, ROTATE, {"translate": [0.3, 0, 0]},
            {"matrix": [1, 0, 0, 0.1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]
IDENTITY16 = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]


def transform_scene(transform=None, transform_end=None, shutter=(0, 1)):
    scene = json.loads(json.dumps(BASE_SCENE))
    if shutter is not None:
        scene["camera"]["shutter"] = list(shutter)
    moving = {"obj": "tri.obj"}
    if transform is not None:
        moving["transform"] = transform
    if transform_end is not None:
        moving["transform_end"] = transform_end
    scene["objects"] = [{"obj": "tri.obj"}, moving]
    return scene


def transform_case(name, scene, expect="any", needle=None):
    # json.dumps writes inf as Infinity (not JSON): 1e999 is the JSON that parses to inf.
    text = scene if isinstance(scene, str) else json.dumps(scene).replace("Infinity", "1e999")
    files = {"tri.obj": TRIANGLE, "scene.json": text}
    case("json-xf-" + name, files, ["render", "scene.json"] + TINY, expect, needle=needle)


def transform_cases():
    transform_case("valid", transform_scene(EVERY_OP, [{"scale": 0.5}, {"translate": [0.5, 0, 0]}]), "ok")
    transform_case("end-without-shutter", transform_scene(EVERY_OP, EVERY_OP[:2], shutter=None), "ok")
    transform_case("end-zero-shutter", transform_scene(None, [ROTATE], shutter=(0.5, 0.5)), "ok")
    bad = [("scale-zero", [{"scale": 0}], "objects[1].transform[0].scale"),
           ("scale-component-zero", [ROTATE, {"scale": [1, 0, 1]}], "objects[1].transform[1].scale"),
           ("translate-huge", [{"translate": [1e999, 0, 0]}], "objects[1].transform[0].translate"),
           ("axis-zero", [{"rotate": {"axis": [0, 0, 0], "angle": 10}}], "objects[1].transform[0].rotate.axis"),
           ("shear", [{"shear": 1}], "objects[1].transform[0].shear"),
           ("two-keys", [{"scale": 2, "translate": [1, 0, 0]}], "objects[1].transform[0]"),
           ("matrix-15", [{"matrix": IDENTITY16[:15]}], "objects[1].transform[0].matrix"),
           ("matrix-projective", [{"matrix": IDENTITY16[:14] + [1, 1]}], "objects[1].transform[0].matrix"),
           ("matrix-singular", [{"matrix": [1, 2, 3, 0, 2, 4, 6, 0, 0, 0, 1, 0, 0, 0, 0, 1]}],
            "objects[1].transform[0].matrix"),
           ("composed-singular", [{"scale": 1e-200}, {"scale": 1e-200}], "objects[1].transform"),
           ("not-a-list", {"scale": 2}, "objects[1].transform")]
    for name, transform, needle in bad:
        transform_case(name, transform_scene(transform), "error", needle=needle)
    transform_case("end-singular", transform_scene(None, [{"scale": [1, 1, 0]}]), "error",
                   needle="objects[1].transform_end[0].scale")
    transform_case("end-singular-without-shutter", transform_scene(None, [{"scale": 1e-200}, {"scale": 1e-200}],
                                                                   shutter=None),
                   "error", needle="objects[1].transform_end")
    for name, shutter in [("shutter-reversed", [1, 0]), ("shutter-one", [0]), ("shutter-number", 1),
                          ("shutter-huge", [0, 1e999])]:
        scene = transform_scene()
        scene["camera"]["shutter"] = shutter
        transform_case(name, scene, "error", needle="camera.shutter")
