# SPDX-License-Identifier: MIT
"""The scene's media (/work/shared/DESIGN.md "Media") as Mitsuba 3 plugins, for
tools/mitsuba_reference.py.

  ours                                     Mitsuba 3.9
  homogeneous sigma_a, sigma_s, scale, g   'homogeneous': sigma_t = (sigma_a + sigma_s) * scale as
                                           sigma_t / max in sigma_t and max in scale (Mitsuba reads
                                           an rgb sigma_t as a reflectance, each value <= 1),
                                           albedo = sigma_s / sigma_t per channel (0 where sigma_t
                                           is 0), phase 'hg' with g (same sign: g > 0 forward)
  grid (.vol) density_scale, sigma_t,      'heterogeneous': sigma_t = gridvolume(file,
  albedo, g                                use_grid_bbox true), scale = density_scale * sigma_t,
                                           albedo constant rgb, phase 'hg' g. Both look the grid
                                           up trilinearly with voxel centres at the voxels'
                                           middles, clamped at the edges, and have no medium
                                           outside the box (tools/mitsuba_media_conventions.py)
  top-level "medium", camera.medium        the sensor's medium (Mitsuba has no world medium: the
                                           camera's medium and the shapes' exteriors are it)
  objects' interior / exterior             the shape's interior / exterior (refs); exterior
                                           defaults to the world medium, and a shape that bounds
                                           no medium gets the world medium on both sides (DESIGN:
                                           it keeps the medium the ray is in)
  material "interface"                     bsdf 'null'

Not translated (each raises SceneError naming the key): emission, NanoVDB files, grids with a
chromatic sigma_t (Mitsuba's heterogeneous takes one density channel times a scalar scale) and grid
transforms.
"""
import os

from mitsuba_obj import SceneError

HOMOGENEOUS_KEYS = {"type", "sigma_a", "sigma_s", "scale", "g", "emission"}
GRID_KEYS = {"type", "file", "grid", "density_scale", "sigma_t", "albedo", "g", "emission", "transform"}


def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


def colour3(value, key, default):
    if value is None:
        value = default
    if isinstance(value, (int, float)):
        return [float(value)] * 3
    if not isinstance(value, list) or len(value) != 3:
        raise SceneError(f"{key}: a number or [r, g, b] expected")
    return [float(x) for x in value]


def is_zero(value):
    return value is None or (value == 0 if isinstance(value, (int, float)) else not any(value))


def ref(name):
    return {"type": "ref", "id": medium_id(name)}


def medium_id(name):
    return f"medium_{name}"


def phase(m, key):
    g = float(m.get("g", 0.0))
    if not -1 < g < 1:
        raise SceneError(f"{key}.g: {g} is not in (-1, 1)")
    return {"type": "hg", "g": g}


def homogeneous(m, key):
    scale = float(m.get("scale", 1.0))
    sa = colour3(m.get("sigma_a"), key + ".sigma_a", 0.0)
    ss = colour3(m.get("sigma_s"), key + ".sigma_s", 0.0)
    st = [(a + s) * scale for a, s in zip(sa, ss)]
    top = max(st)
    if top <= 0:
        raise SceneError(f"{key}: sigma_a + sigma_s is 0 (an empty medium)")
    albedo = [s * scale / t if t > 0 else 0.0 for s, t in zip(ss, st)]
    return {"type": "homogeneous", "sigma_t": rgb([t / top for t in st]), "scale": top,
            "albedo": rgb(albedo), "phase": phase(m, key)}


def grid(m, key, base_dir):
    path = os.path.join(base_dir, m.get("file", ""))
    if not path.endswith(".vol"):
        raise SceneError(f"{key}.file: only Mitsuba .vol grids are translated")
    if not os.path.exists(path):
        raise SceneError(f"{key}.file: {path} not found")
    if "transform" in m:
        raise SceneError(f"{key}.transform: not translated")
    sigma_t = colour3(m.get("sigma_t"), key + ".sigma_t", 1.0)
    if len(set(sigma_t)) != 1:
        raise SceneError(f"{key}.sigma_t: a chromatic sigma_t on a grid is not translated "
                         "(Mitsuba's heterogeneous has one density channel)")
    return {"type": "heterogeneous",
            "sigma_t": {"type": "gridvolume", "filename": path, "use_grid_bbox": True},
            "scale": float(m.get("density_scale", 1.0)) * sigma_t[0],
            "albedo": rgb(colour3(m.get("albedo"), key + ".albedo", 1.0)), "phase": phase(m, key)}


class Media:
    """The scene's "media", "medium" and camera.medium; plugins() gives the Mitsuba media (top-level
    objects that shapes and the sensor refer to by id)."""

    def __init__(self, scene, base_dir):
        self.media = scene.get("media", {})
        self.base_dir = base_dir
        for name, m in self.media.items():
            key = f"media.{name}"
            kind = m.get("type")
            allowed = {"homogeneous": HOMOGENEOUS_KEYS, "grid": GRID_KEYS}.get(kind)
            if allowed is None:
                raise SceneError(f"{key}.type: '{kind}' is not a medium type")
            for k in m:
                if k not in allowed:
                    raise SceneError(f"{key}.{k}: not translated")
            if not is_zero(m.get("emission")):
                raise SceneError(f"{key}.emission: emitting media are not translated")
        self.world = self.check(scene.get("medium"), "medium")
        self.camera = self.check(scene.get("camera", {}).get("medium", self.world), "camera.medium")

    def check(self, name, key):
        if name is not None and name not in self.media:
            raise SceneError(f"{key}: no medium '{name}'")
        return name

    def __bool__(self):
        return bool(self.media)

    def plugins(self):
        out = {}
        for name, m in self.media.items():
            key = f"media.{name}"
            out[medium_id(name)] = homogeneous(m, key) if m["type"] == "homogeneous" else grid(
                m, key, self.base_dir)
        return out

    def shape_media(self, obj, key, absorption=None):
        """The shape's interior/exterior entries for object `obj` (a dict to merge into the shape);
        `absorption` is the interior medium a dielectric's absorption makes (or None)."""
        interior = self.check(obj.get("interior"), key + ".interior")
        exterior = self.check(obj.get("exterior", self.world), key + ".exterior")
        out = {}
        if interior is not None:
            if absorption is not None:
                raise SceneError(f"{key}.interior: the material has an absorption too")
            out["interior"] = ref(interior)
        elif absorption is not None:
            out["interior"] = absorption
        elif "interior" not in obj and "exterior" not in obj and self.world is not None:
            out["interior"] = ref(self.world)  # bounds no medium: keeps the world's on both sides
        if exterior is not None:
            out["exterior"] = ref(exterior)
        return out

    def sensor_medium(self):
        return ref(self.camera) if self.camera is not None else None
