# SPDX-License-Identifier: MIT
"""The scene's analytic `lights` (/work/shared/DESIGN.md "Lights") as Mitsuba 3 emitters, for
tools/mitsuba_reference.py.

  ours                                        Mitsuba 3.9
  point position, intensity (W/sr)            'point' position, intensity
  spot position, direction, intensity,        'spot' intensity, cutoff_angle = cone_angle,
  cone_angle (30), falloff_angle (= cone)     beam_width = falloff_angle, to_world looking along
                                              direction. Both: full intensity inside the beam,
                                              falling linearly in angle to 0 at the cutoff
                                              (Mitsuba's spot.cpp falloff_curve)
  directional direction, irradiance           'directional' direction, irradiance

`sun` (a disc) is not translated: SceneError.
"""
import math

from mitsuba_obj import SceneError

KEYS = {"point": {"position", "intensity"},
        "spot": {"position", "direction", "intensity", "cone_angle", "falloff_angle"},
        "directional": {"direction", "irradiance"}}


def rgb(c):
    c = [c] * 3 if isinstance(c, (int, float)) else c
    return {"type": "rgb", "value": [float(x) for x in c]}


def emitters(scene, mi):
    """{id: emitter} for the scene's lights."""
    out = {}
    for i, light in enumerate(scene.get("lights", [])):
        key = f"lights[{i}]"
        kind = light.get("type")
        if kind not in KEYS:
            raise SceneError(f"{key}.type: '{kind}' is not translated")
        for k in light:
            if k != "type" and k not in KEYS[kind]:
                raise SceneError(f"{key}.{k}: not translated")
        if kind == "point":
            e = {"type": "point", "position": [float(x) for x in light["position"]],
                 "intensity": rgb(light["intensity"])}
        elif kind == "directional":
            e = {"type": "directional", "direction": [float(x) for x in light["direction"]],
                 "irradiance": rgb(light["irradiance"])}
        else:
            cone = float(light.get("cone_angle", 30.0))
            falloff = min(float(light.get("falloff_angle", cone)), cone)
            # Mitsuba divides by cutoff - beam_width: keep the (empty) transition a hair wide.
            beam = min(falloff, cone - 1e-4)
            p = [float(x) for x in light["position"]]
            d = [float(x) for x in light["direction"]]
            norm = math.sqrt(sum(x * x for x in d))
            d = [x / norm for x in d]
            up = [0, 1, 0] if abs(d[1]) < 0.9 else [1, 0, 0]  # the spot is symmetric about its axis
            e = {"type": "spot", "intensity": rgb(light["intensity"]), "cutoff_angle": cone,
                 "beam_width": beam,
                 "to_world": mi.ScalarTransform4f().look_at(
                     origin=p, target=[p[k] + d[k] for k in range(3)], up=up)}
        out[f"light{i}_{kind}"] = e
    return out
