#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline for tests/mitsuba/materials.pts.

  python3 scripts/mitsuba_materials.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/materials_ref_<res>_<ref-spp>spp.exr and the
"materials" entry of tests/mitsuba/baseline.json. The scene is written by
hand, the same as materials.pts: every BSDF with `ext_ior` 1 (Mitsuba's
default is air's 1.000277; ptsc's outside is 1), GGX with visible-normal
sampling, and the metals' eta and k given as ptsc's presets (the values
Mitsuba's `material` "Au" and "Cu" give in scalar_rgb, copied into
ptsc::material::conductor::PRESETS).
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

GOLD = ([0.143036, 0.375307, 1.44205], [3.983, 2.38556, 1.60336])
COPPER = ([0.201005, 0.92375, 1.10222], [3.91326, 2.45305, 2.14209])


def ball(x, z, bsdf):
    return {"type": "sphere", "center": [x, 0.5, z], "radius": 0.5, "bsdf": bsdf}


def stage(res, spp):
    """The scene around the six balls: camera, studio map, floor (shared
    with mitsuba_material_options.py)."""
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": sensor(res, spp, [0, 2.2, 5], [0, 0.5, 0], 40.0, [0, 1, 0]),
        "sky": {"type": "envmap", "filename": str(ROOT / "examples" / "images" / "studio.exr"), "scale": 0.8},
        "floor": rectangle([-4, 0, 3], [8, 0, 0], [0, 0, -7], {"type": "diffuse", "reflectance": rgb([0.5] * 3)}),
    }


def scene(res, spp):
    ior = {"int_ior": 1.5, "ext_ior": 1.0}
    return {
        **stage(res, spp),
        "gold": ball(-1.2, -0.8, {"type": "conductor", "eta": rgb(GOLD[0]), "k": rgb(GOLD[1])}),
        "copper": ball(0, -0.8, {"type": "roughconductor", "distribution": "ggx", "alpha": 0.1,
                                 "eta": rgb(COPPER[0]), "k": rgb(COPPER[1])}),
        "frosted": ball(1.2, -0.8, {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.2, **ior}),
        "plastic": ball(-1.2, 0.6, {"type": "plastic", "diffuse_reflectance": rgb([0.7, 0.1, 0.1]), **ior}),
        "rough_plastic": ball(0, 0.6, {"type": "roughplastic", "distribution": "ggx", "alpha": 0.2,
                                       "diffuse_reflectance": rgb([0.1, 0.2, 0.6]), **ior}),
        "bubble": ball(1.2, 0.6, {"type": "thindielectric", **ior}),
    }


def main():
    mi.set_variant("scalar_rgb")
    reference_and_baseline("materials", scene, 16)


if __name__ == "__main__":
    main()
