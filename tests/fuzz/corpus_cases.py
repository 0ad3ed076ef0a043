# SPDX-License-Identifier: MIT
"""The case list every corpus_*.py module appends to (gen_corpus.py writes it out; its docstring
says what each field means), and the inputs the modules share.
"""

TINY = ["--width", "8", "--height", "8", "--spp", "1", "--max-depth", "2", "--device", "cpu",
        "--quiet", "-o", "out.png"]
TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
TEXTURED = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3\n"
BASE_SCENE = {
    "camera": {"eye": [0.3, 0.3, 2], "target": [0.3, 0.3, 0], "up": [0, 1, 0], "fov_y": 40},
    "film": {"width": 8, "height": 8},
    "render": {"spp": 1, "max_depth": 2},
    "objects": [{"obj": "tri.obj"}],
    "background": [1, 1, 1],
}

# Filled in generation order: a case's index is part of its folder name.
cases = []


def case(name, files, args, expect="any", env=None, needle=None, setup=None, known=None,
         timeout=None):
    cases.append(dict(name=name, files=files, args=args, expect=expect, env=env or {},
                      needle=needle, setup=setup, known=known, timeout=timeout))
