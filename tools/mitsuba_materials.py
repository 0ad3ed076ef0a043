# SPDX-License-Identifier: MIT
"""The JSON materials, textures and environment of a v2 scene (/work/shared/DESIGN.md "Materials",
"Textures", "Environment") as Mitsuba 3 plugins, for tools/mitsuba_reference.py.

  ours                                    Mitsuba 3.9
  diffuse albedo                          diffuse reflectance
  conductor r = 0                         conductor (eta/k as rgb; neither = material 'none', Fresnel 1)
  conductor r > 0                         roughconductor, ggx, sample_visible, alpha = r^2, or with
                                          anisotropy a: alpha_u = r^2/sqrt(1-0.9a), alpha_v = r^2 sqrt(1-0.9a)
                                          (Mitsuba's s axis is dp/du, checked in tests/references/README.md)
  reflectance                             specular_reflectance
  dielectric                              dielectric / roughdielectric (ggx, sample_visible), int_ior,
                                          ext_ior 1, specular_transmittance = tint; not two-sided
  absorption sigma                        interior 'homogeneous' medium, sigma_t = sigma, albedo 0
                                          (pure absorption: transmittance exp(-sigma d)); the
                                          integrator becomes volpath
  mix a, b, weight w                      blendbsdf(a, b, weight w): (1 - w) a + w b
  normal_map                              normalmap (raw texels, n = 2 t - 1; its frame is (dp/du,
                                          n x dp/du, n): DESIGN's for UVs that are not mirrored),
                                          use_shadowing_function false (DESIGN: no terminator term)
  emission x emission_strength            'area' emitter
  interface (media boundary)              null (tools/mitsuba_media.py gives the shape its media)
  non-dielectrics                         wrapped in twosided (ours shade the side a ray arrives from)
  environment file, scale, rotation t     envmap, scale, to_world = rotation about +y by 180 + t
                                          degrees (Mitsuba puts u = 0 where we put u = 0.5); the rows
                                          resampled so that Mitsuba's bilinear lookup gives ours
                                          exactly (mitsuba_rows)

principled is not translated: Mitsuba's 'principled' is Disney's BRDF, not glTF's model, so no
reference of ours would test what DESIGN defines. Neither are textured roughness/weight maps,
bump maps, opacity and noise textures: each raises SceneError naming the key.
"""
import os

from mitsuba_obj import SceneError

MATERIAL_KEYS = {
    "diffuse": {"albedo"},
    "conductor": {"roughness", "eta", "k", "reflectance", "anisotropy"},
    "dielectric": {"ior", "roughness", "tint", "absorption"},
    "mix": {"a", "b", "weight"},
    "interface": set(),
}
COMMON_KEYS = {"type", "emission", "emission_strength", "normal_map"}


def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


class JsonMaterials:
    """The scene's "materials" and "textures" blocks; bsdf(name) builds one material's plugins."""

    def __init__(self, scene, base_dir, mi, np):
        self.materials = scene.get("materials", {})
        self.textures = scene.get("textures", {})
        self.base_dir, self.mi, self.np = base_dir, mi, np
        for name, m in self.materials.items():
            kind = m.get("type")
            if kind == "principled":
                raise SceneError(f"materials.{name}: principled has no Mitsuba equivalent (Mitsuba's "
                                 "principled is Disney's BRDF, not glTF's)")
            if kind not in MATERIAL_KEYS:
                raise SceneError(f"materials.{name}.type: '{kind}' is not translated")
            for k in m:
                if k not in MATERIAL_KEYS[kind] | COMMON_KEYS:
                    raise SceneError(f"materials.{name}.{k}: not translated")

    def __contains__(self, name):
        return name in self.materials

    # ---- values ----------------------------------------------------------------------------------

    def texture(self, name, key, linear=False):
        t = self.textures.get(name)
        if t is None:
            raise SceneError(f"{key}: no texture '{name}'")
        if t.get("type", "file") != "file" or "file" not in t:
            raise SceneError(f"textures.{name}: only file textures are translated")
        path = os.path.join(self.base_dir, t["file"])
        if not os.path.exists(path):
            raise SceneError(f"textures.{name}: {path} not found")
        raw = linear or t.get("encoding", "srgb") == "linear"
        return {"type": "bitmap", "filename": path, "filter_type": "bilinear",
                "wrap_mode": "repeat", "raw": raw}

    def colour(self, value, key, default):
        if value is None:
            value = default
        if isinstance(value, str):
            return self.texture(value, key)
        if isinstance(value, (int, float)):
            return rgb([value] * 3)
        return rgb(value)

    def scalar(self, value, key, default):
        if value is None:
            return float(default)
        if isinstance(value, str):
            raise SceneError(f"{key}: textured scalars are not translated")
        return float(value)

    # ---- materials -------------------------------------------------------------------------------

    def lobe(self, name, depth=0):
        """The material's BSDF without the two-sided wrapper; returns (bsdf, interior medium)."""
        if depth > 8:
            raise SceneError(f"materials.{name}: mixes nested too deep (a cycle?)")
        m = self.materials[name]
        key = f"materials.{name}"
        kind = m["type"]
        medium = None
        if kind == "interface":
            return {"type": "null"}, None
        if kind == "diffuse":
            bsdf = {"type": "diffuse", "reflectance": self.colour(m.get("albedo"), key + ".albedo", 0.8)}
        elif kind == "conductor":
            r = self.scalar(m.get("roughness"), key + ".roughness", 0.0)
            bsdf = {"type": "conductor" if r == 0 else "roughconductor",
                    "specular_reflectance": self.colour(m.get("reflectance"), key + ".reflectance", 1.0)}
            if "eta" in m or "k" in m:
                bsdf["eta"] = self.colour(m.get("eta"), key + ".eta", 1.0)
                bsdf["k"] = self.colour(m.get("k"), key + ".k", 0.0)
            else:
                bsdf["material"] = "none"
            if r > 0:
                bsdf.update(distribution="ggx", sample_visible=True)
                a = self.scalar(m.get("anisotropy"), key + ".anisotropy", 0.0)
                if a > 0:
                    s = (1 - 0.9 * a) ** 0.5
                    bsdf.update(alpha_u=r * r / s, alpha_v=r * r * s)
                else:
                    bsdf["alpha"] = r * r
        elif kind == "dielectric":
            r = self.scalar(m.get("roughness"), key + ".roughness", 0.0)
            bsdf = {"type": "dielectric" if r == 0 else "roughdielectric",
                    "int_ior": self.scalar(m.get("ior"), key + ".ior", 1.5), "ext_ior": 1.0,
                    "specular_transmittance": self.colour(m.get("tint"), key + ".tint", 1.0)}
            if r > 0:
                bsdf.update(distribution="ggx", sample_visible=True, alpha=r * r)
            sigma = m.get("absorption", 0.0)
            sigma = [sigma] * 3 if isinstance(sigma, (int, float)) else sigma
            if any(s > 0 for s in sigma):
                # Mitsuba reads an rgb sigma_t as a reflectance (each value <= 1): scale carries the size.
                top = max(sigma)
                medium = {"type": "homogeneous", "sigma_t": rgb([s / top for s in sigma]),
                          "scale": float(top), "albedo": rgb([0, 0, 0])}
        else:  # mix
            parts = []
            for k in ("a", "b"):
                if m.get(k) not in self.materials:
                    raise SceneError(f"{key}.{k}: no JSON material '{m.get(k)}'")
                if self.materials[m[k]]["type"] == "dielectric":
                    raise SceneError(f"{key}.{k}: mixes with a dielectric are not translated")
                parts.append(self.lobe(m[k], depth + 1)[0])
            bsdf = {"type": "blendbsdf", "weight": self.scalar(m.get("weight"), key + ".weight", 0.5),
                    "bsdf_0": parts[0], "bsdf_1": parts[1]}
        if "normal_map" in m:
            # Mitsuba >= 3.7.1 multiplies by Conty Estevez et al.'s shadow-terminator term unless
            # told not to; DESIGN has none. (Its flip_invalid_normals, on, only acts where the
            # camera sees the back of the perturbed normal.)
            bsdf = {"type": "normalmap", "bsdf": bsdf, "use_shadowing_function": False,
                    "normalmap": self.texture(m["normal_map"], key + ".normal_map", linear=True)}
        return bsdf, medium

    def bsdf(self, name):
        """(bsdf, interior medium or None, emitted radiance or None) of material `name`."""
        m = self.materials[name]
        bsdf, medium = self.lobe(name)
        if m["type"] not in ("dielectric", "interface"):
            bsdf = {"type": "twosided", "material": bsdf}
        emission = None
        if "emission" in m:
            e = m["emission"]
            if isinstance(e, str):
                raise SceneError(f"materials.{name}.emission: textured emission is not translated")
            e = [e] * 3 if isinstance(e, (int, float)) else e
            strength = float(m.get("emission_strength", 1.0))
            if any(c > 0 for c in e) and strength > 0:
                emission = [c * strength for c in e]
        return bsdf, medium, emission


def mitsuba_rows(texels, np):
    """Our H rows resampled into the 2H + 1 rows Mitsuba's envmap needs to show the same bilinear
    radiance. Ours puts row j at v = (j + 0.5)/H (clamped at the poles), Mitsuba puts row r at
    v = r/(rows - 1) (row 0 on the north pole): with 2H + 1 rows, the odd ones are ours and the even
    ones the midpoints between ours, so every kink of our piecewise-bilinear function is one of
    Mitsuba's knots and its interpolation reproduces ours exactly. Columns need nothing: both put
    column i at u = (i + 0.5)/W and wrap (u itself is turned by to_world)."""
    h = texels.shape[0]
    out = np.empty((2 * h + 1,) + texels.shape[1:], dtype=np.float32)
    out[1::2] = texels
    out[0], out[-1] = texels[0], texels[-1]
    out[2:-1:2] = 0.5 * (texels[:-1] + texels[1:])
    return out


def environment_emitter(env, base_dir, mi, np):
    """Our environment block as a Mitsuba envmap (see the table above)."""
    path = os.path.join(base_dir, env["file"])
    if not os.path.exists(path):
        raise SceneError(f"environment.file: {path} not found")
    bitmap = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                     srgb_gamma=False)
    texels = mitsuba_rows(np.array(bitmap), np)
    return {"type": "envmap", "bitmap": mi.Bitmap(np.ascontiguousarray(texels, dtype=np.float32)),
            "scale": float(env.get("scale", 1.0)),
            "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], 180.0 + float(env.get("rotation", 0.0)))}
