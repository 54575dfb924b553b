#!/usr/bin/env python3
"""Mitsuba 3's `principled` BSDF evaluated at random direction pairs, for
ptsc's value-for-value comparison (tests/integration/materials.rs,
`principled_matches_mitsuba_value_for_value`).

Writes tests/mitsuba/principled_eval.json: per configuration (a grid of
metallic 0 / 0.5 / 1 × roughness 0.1 / 0.5 / 0.9, then specular with its
tint, clearcoat, sheen, transmission and anisotropy) the parameters in
ptsc's words and, per pair, the view `wo` (Mitsuba's si.wi), the light
direction `wi` (Mitsuba's wo), Mitsuba's eval (f·|cos θ|, RGB) and pdf.

    pip install mitsuba==3.9.1
    python3 scripts/mitsuba_principled.py
"""
import json
import math
import os
import random

import mitsuba as mi

mi.set_variant("scalar_rgb")

BASE = [0.8, 0.4, 0.2]
PAIRS = 48


def configs():
    """(ptsc parameters, Mitsuba parameters) of each configuration."""
    out = []
    for metallic in [0.0, 0.5, 1.0]:
        for roughness in [0.1, 0.5, 0.9]:
            out.append(dict(metallic=metallic, roughness=roughness))
    out += [
        dict(roughness=0.4, specular=0.2, specular_tint=0.5),
        dict(roughness=0.4, specular=0.9, specular_tint=1.0, metallic=0.3),
        dict(roughness=0.5, clearcoat=1.0, clearcoat_roughness=0.7),
        dict(roughness=0.3, clearcoat=0.5, clearcoat_roughness=0.0, metallic=0.5),
        dict(roughness=0.6, sheen=1.0, sheen_tint=0.5),
        dict(roughness=0.3, transmission=1.0),
        dict(roughness=0.5, transmission=0.6, metallic=0.2, specular=0.7),
        dict(roughness=0.4, anisotropic=0.7, metallic=0.8),
    ]
    return out


def mitsuba_params(c):
    p = {"type": "principled", "base_color": {"type": "rgb", "value": BASE}}
    for key, value in c.items():
        if key == "transmission":
            p["spec_trans"] = value
        elif key == "specular_tint":
            p["spec_tint"] = value
        elif key == "clearcoat_roughness":
            p["clearcoat_gloss"] = 1.0 - value
        else:
            p[key] = value
    return p


def direction(rng, lower):
    z = rng.uniform(-1.0, 1.0) if lower else rng.uniform(0.02, 1.0)
    phi = rng.uniform(0.0, 2.0 * math.pi)
    s = math.sqrt(max(0.0, 1.0 - z * z))
    return [s * math.cos(phi), s * math.sin(phi), z]


def about_normal(rng, wo, c, refract):
    """`wo` reflected or refracted about a normal near +z."""
    m = [rng.gauss(0.0, 0.25), rng.gauss(0.0, 0.25), 1.0]
    n = math.sqrt(sum(x * x for x in m))
    m = [x / n for x in m]
    if wo[2] < 0:
        m = [-x for x in m]
    c_o = sum(a * b for a, b in zip(wo, m))
    if not refract:
        return [2 * c_o * b - a for a, b in zip(wo, m)]
    specular = c.get("specular", 0.5)
    eta = 2.0 / (1.0 - math.sqrt(0.08 * specular)) - 1.0
    eta = eta if wo[2] > 0 else 1.0 / eta
    sin2_t = max(0.0, 1.0 - c_o * c_o) / (eta * eta)
    if sin2_t >= 1.0 or c_o <= 0:
        return None
    cos_t = math.sqrt(1.0 - sin2_t)
    return [-a / eta + (c_o / eta - cos_t) * b for a, b in zip(wo, m)]


def main():
    rng = random.Random(7)
    out = {"base_color": BASE, "configs": []}
    for c in configs():
        bsdf = mi.load_dict(mitsuba_params(c))
        lower = "transmission" in c
        pairs = []
        while len(pairs) < PAIRS:
            wo = direction(rng, lower)
            wi = direction(rng, True)
            if len(pairs) % 2 == 1:
                # Near the specular lobes: wo mirrored (or refracted) about a
                # normal tilted a little from +z.
                wi = about_normal(rng, wo, c, refract=lower and len(pairs) % 4 == 3)
                if wi is None:
                    continue
            if abs(wo[2]) < 0.02 or abs(wi[2]) < 0.02:
                continue
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(wo)
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            ctx = mi.BSDFContext()
            value = bsdf.eval(ctx, si, mi.Vector3f(wi))
            pdf = bsdf.pdf(ctx, si, mi.Vector3f(wi))
            pairs.append(
                {
                    "wo": wo,
                    "wi": wi,
                    "value": [float(value[0]), float(value[1]), float(value[2])],
                    "pdf": float(pdf),
                }
            )
        out["configs"].append({"params": c, "pairs": pairs})
    path = os.path.join(os.path.dirname(__file__), "..", "tests", "mitsuba", "principled_eval.json")
    with open(path, "w") as f:
        json.dump(out, f)
    print("wrote", os.path.normpath(path))


if __name__ == "__main__":
    main()
