# SPDX-License-Identifier: MIT
"""The "black_holes" array: valid holes (with and without a disk) render, bad values are one-line
errors naming the key (README "Black holes")."""
import json

from corpus_cases import BASE_SCENE


def black_holes_cases(scene_case):
    disk = {"normal": [0, 1, 0.2], "inner_radius": 0.3, "outer_radius": 1.0, "emission": [2, 1, 0.5],
            "temperature": 6000, "opacity": 0.7, "noise": {"frequency": 2, "octaves": 3, "swirl": 4}}
    good = {"plain": {"position": [0.3, 0.3, -1], "mass": 0.05},
            "disk": {"position": [0.3, 0.3, -1], "mass": 0.05, "disk": disk},
            "massless": {"position": [0.3, 0.3, 2], "mass": 0},
            "influence": {"position": [0.3, 0.3, -1], "mass": 0.05, "influence_radius": 3}}
    for name, hole in good.items():
        scene = json.loads(json.dumps(BASE_SCENE))
        scene["black_holes"] = [hole]
        scene_case("black-holes-valid-%s" % name, json.dumps(scene), "ok")
    bad = [("negative-mass", {"mass": -1}), ("string-mass", {"mass": "1"}),
           ("huge-mass", {"mass": 1e300}), ("no-position", {"position": None}),
           ("short-position", {"position": [0, 0]}), ("extra-key", {"spin": 0.9}),
           ("inner-over-outer", {"disk": dict(disk, inner_radius=2.0)}),
           ("inner-in-horizon", {"disk": dict(disk, inner_radius=0.05)}),
           ("no-outer", {"disk": {"inner_radius": 0.3}}),
           ("opacity-over-one", {"disk": dict(disk, opacity=2)}),
           ("cold-disk", {"disk": dict(disk, temperature=10)}),
           ("octaves-fraction", {"disk": dict(disk, noise={"octaves": 1.5})}),
           ("zero-normal", {"disk": dict(disk, normal=[0, 0, 0])}),
           ("influence-inside-disk", {"disk": disk, "influence_radius": 0.5})]
    for name, change in bad:
        scene = json.loads(json.dumps(BASE_SCENE))
        hole = {"position": [0.3, 0.3, -1], "mass": 0.05}
        hole.update(change)
        hole = {k: v for k, v in hole.items() if v is not None}
        scene["black_holes"] = [hole]
        scene_case("black-holes-%s" % name, json.dumps(scene), "error", needle="black_holes[0]")
    scene = json.loads(json.dumps(BASE_SCENE))
    scene["black_holes"] = [{"position": [0.3, 0.3, 1.95], "mass": 0.05}]
    scene_case("black-holes-camera-inside", json.dumps(scene), "error", needle="camera.eye")
    scene["black_holes"] = [{"position": [0, 0, -1], "mass": 0.05}, {"position": [0.1, 0, -1], "mass": 0.05}]
    scene_case("black-holes-overlap", json.dumps(scene), "error", needle="black_holes[1]")
    scene["black_holes"] = {"mass": 1}
    scene_case("black-holes-not-an-array", json.dumps(scene), "error", needle="black_holes")
