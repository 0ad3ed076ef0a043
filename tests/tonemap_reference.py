#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The tabulated values of tests/test_tonemap.c, computed in double from the published reference
code, written independently of host/io/display_curve.h: matrices as the references give them
(GLSL mat3 constructors are column-major) and inverted here, vectors as the references treat them.
Prints the C table; run it and paste when a reference changes.
  agx:          three.js tonemapping_pars_fragment.glsl.js, AgXToneMapping (r160+)
  aces:         Stephen Hill, BakingLab ACES.hlsl (ACESFitted, no 1/0.6)
  filmic:       John Hable, "Filmic Tonemapping Operators" (2010), Uncharted2Tonemap, W 11.2, bias 2
  pbr-neutral:  KhronosGroup/ToneMapping PBR_Neutral/README.md (specification)
  reinhard:     three.js ReinhardToneMapping (per channel x / (1 + x))
Each returns display-linear values in [0, 1] (before the sRGB OETF)."""
import math


def mat_cols(c0, c1, c2):  # GLSL mat3(vec3, vec3, vec3): columns
    return [[c0[i], c1[i], c2[i]] for i in range(3)]


def mat_rows(r0, r1, r2):
    return [list(r0), list(r1), list(r2)]


def mul(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def inverse(m):
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def sat(v):
    return [min(max(x, 0.0), 1.0) for x in v]


def agx(c):
    rec2020_to_srgb = mat_rows((1.6605, -0.5876, -0.0728), (-0.1246, 1.1329, -0.0083),
                               (-0.0182, -0.1006, 1.1187))
    srgb_to_rec2020 = inverse(rec2020_to_srgb)
    inset = mat_cols((0.856627153315983, 0.137318972929847, 0.11189821299995),
                     (0.0951212405381588, 0.761241990602591, 0.0767994186031903),
                     (0.0482516061458583, 0.101439036467562, 0.811302368396859))
    outset = inverse(mat_cols((0.899796955911611, 0.11142098895748, 0.11142098895748),
                              (0.0871996192028351, 0.875575586156966, 0.0871996192028349),
                              (0.013003424885555, 0.0130034248855548, 0.801379391839686)))
    lo, hi = -12.47393, 4.026069
    v = [max(0.0, x) for x in mul(srgb_to_rec2020, c)]
    v = mul(inset, v)
    v = [min(max((math.log2(max(x, 1e-10)) - lo) / (hi - lo), 0.0), 1.0) for x in v]
    v = [15.5 * x**6 - 40.14 * x**5 + 31.96 * x**4 - 6.868 * x**3 + 0.4298 * x**2 + 0.1191 * x
         - 0.00232 for x in v]
    v = mul(outset, v)
    v = [max(0.0, x) ** 2.2 for x in v]
    return sat(mul(rec2020_to_srgb, v))


def aces(c):
    aces_in = mat_rows((0.59719, 0.35458, 0.04823), (0.07600, 0.90834, 0.01566),
                       (0.02840, 0.13383, 0.83777))
    aces_out = mat_rows((1.60475, -0.53108, -0.07367), (-0.10208, 1.10813, -0.00605),
                        (-0.00327, -0.07276, 1.07602))
    v = mul(aces_in, c)
    v = [(x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.4329510) + 0.238081)
         for x in v]
    return sat(mul(aces_out, v))


def hable(x):
    A, B, C, D, E, F = 0.15, 0.50, 0.10, 0.20, 0.02, 0.30
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F


def filmic(c):
    return sat([hable(2.0 * x) / hable(11.2) for x in c])


def pbr_neutral(c):
    f90, ks, kd = 0.04, 0.8 - 0.04, 0.15
    x = min(c)
    f = x - x * x / (4 * f90) if x <= 2 * f90 else f90
    p = max(y - f for y in c)
    if p <= ks:
        return sat([y - f for y in c])
    pn = 1 - (1 - ks) ** 2 / (p + 1 - 2 * ks)
    g = 1 / (kd * (p - pn) + 1)
    return sat([(y - f) * pn / p * g + pn * (1 - g) for y in c])


def reinhard(c):
    return sat([x / (1 + x) for x in c])


def clamp(c):
    return sat(c)


INPUTS = [(0.0, 0.0, 0.0), (0.01, 0.01, 0.01), (0.18, 0.18, 0.18), (0.5, 0.2, 0.05),
          (1.0, 1.0, 1.0), (2.0, 0.5, 0.1), (0.1, 0.4, 3.0), (16.0, 16.0, 16.0),
          (100.0, 60.0, 10.0)]
CURVES = [("AGX", agx), ("ACES", aces), ("FILMIC", filmic), ("PBR_NEUTRAL", pbr_neutral),
          ("REINHARD", reinhard), ("CLAMP", clamp)]

if __name__ == "__main__":
    for name, curve in CURVES:
        for c in INPUTS:
            out = curve(list(c))
            values = (name,) + c + tuple(out)
            print("    {TONEMAP_%s, {%.9g, %.9g, %.9g}, {%.9g, %.9g, %.9g}}," % values)
