#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline of tests/mitsuba/capsule.pts: a
diffuse capsule under a square lamp and a glowing capsule (a tube lamp).

  python3 scripts/mitsuba_capsule.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/capsule_ref_<res>_<ref-spp>spp.exr and the capsule
entry of tests/mitsuba/baseline.json. Mitsuba has no capsule: each is an
open `cylinder` from base to top (Mitsuba's has no caps) and a `sphere` of
the same radius at each end. For an opaque object that is the same visible
surface: the spheres' inner halves lie inside the cylinder, where no ray
from outside reaches; on the lamp they emit into its inside (Mitsuba's
area emitters emit on the side their normal faces), where the black
cylinder and spheres absorb it. ptsc's diffuse reflects on both sides,
Mitsuba's only on the side its normal faces: the walls are `twosided`.
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402


def diffuse(v):
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(v)}}


def capsule(key, base, top, radius, bsdf, emission=None):
    """The capsule's three pieces as entries `key_side`, `key_base`,
    `key_top` of the scene."""
    pieces = {
        f"{key}_side": {"type": "cylinder", "p0": base, "p1": top, "radius": radius},
        f"{key}_base": {"type": "sphere", "center": base, "radius": radius},
        f"{key}_top": {"type": "sphere", "center": top, "radius": radius},
    }
    for piece in pieces.values():
        piece["bsdf"] = bsdf
        if emission is not None:
            piece["emitter"] = {"type": "area", "radiance": rgb(emission)}
    return pieces


def scene(res, spp):
    wall = diffuse([0.6] * 3)
    black = {"type": "diffuse", "reflectance": rgb([0, 0, 0])}
    lamp = rectangle([-0.6, 2.4, -0.6], [1.2, 0, 0], [0, 0, 1.2], black)
    lamp["emitter"] = {"type": "area", "radiance": rgb([6, 6, 6])}
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1.3, 4.2], [0, 0.8, 0], 45.0),
        "background": {"type": "constant", "radiance": rgb([0.05] * 3)},
        "floor": rectangle([-2, 0, 2], [4, 0, 0], [0, 0, -4], wall),
        "back": rectangle([-2, 0, -2], [4, 0, 0], [0, 2.5, 0], wall),
        "left": rectangle([-2, 0, 2], [0, 0, -4], [0, 2.5, 0], diffuse([0.6, 0.2, 0.15])),
        "lamp": lamp,
        **capsule("capsule", [-0.8, 0.45, 0.3], [0.5, 1.0, -0.4], 0.4, diffuse([0.2, 0.45, 0.7])),
        **capsule("tube", [-1.3, 0.12, -1.5], [1.3, 0.12, -1.5], 0.1, black, [5, 3.5, 2]),
    }


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    reference_and_baseline("capsule", scene, 16)


if __name__ == "__main__":
    main()
