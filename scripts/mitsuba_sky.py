#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline for tests/mitsuba/sky.pts.

  python3 scripts/mitsuba_sky.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/sky_ref_<res>_<ref-spp>spp.exr and the "sky" entry of
tests/mitsuba/baseline.json. The scene is written by hand, the same as
sky.pts: Mitsuba's `sunsky` is z-up, so ptsc's (x, y, z) is Mitsuba's
(x, -z, y) here (a rotation: ptsc's -z, ahead, is Mitsuba's +y), applied
to the sun's direction and to every position.
"""
import math
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402


def m(p):
    """ptsc's (x, y, z), y up, as Mitsuba's z-up (x, -z, y)."""
    return [p[0], -p[2], p[1]]


def sun_direction(elevation, azimuth):
    """ptsc's sun direction (y up, azimuth from -z towards +x), in degrees."""
    el, az = math.radians(elevation), math.radians(azimuth)
    return [math.sin(az) * math.cos(el), math.sin(el), -math.cos(az) * math.cos(el)]


def scene(res, spp):
    sun = sun_direction(30, 60)
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, m([0, 1, 4]), m([0, 0.4, 0]), 45.0, m([0, 1, 0])),
        "sky": {"type": "sunsky", "sun_direction": m(sun), "turbidity": 3.0, "albedo": 0.3},
        "floor": rectangle(m([-3, 0, 3]), m([6, 0, 0]), m([0, 0, -6]), {"type": "diffuse", "reflectance": rgb([0.5] * 3)}),
        "ball": {"type": "sphere", "center": m([-0.6, 0.5, 0]), "radius": 0.5,
                 "bsdf": {"type": "diffuse", "reflectance": rgb([0.8] * 3)}},
        "mirror": {"type": "sphere", "center": m([0.6, 0.5, -0.3]), "radius": 0.5,
                   "bsdf": {"type": "roughconductor", "material": "none", "distribution": "ggx", "alpha": 0.09,
                            "specular_reflectance": rgb([0.9] * 3)}},
    }


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    reference_and_baseline("sky", scene, 16)


if __name__ == "__main__":
    main()
