#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline for tests/mitsuba/envmap.pts.

  python3 scripts/mitsuba_envmap.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 32]

Writes tests/mitsuba/envmap_ref_<res>_<ref-spp>spp.exr (Mitsuba's `path`,
scalar_rgb) and the "envmap" entry of tests/mitsuba/baseline.json. The
scene is written by hand, the same as envmap.pts: Mitsuba's `envmap` with
`scale` 0.8 (ptsc's `intensity rgb 0.8`); both read the map with the same
convention (u = atan2(x, -z) / 2 pi, v = acos(y) / pi, texels at grid
points, bilinear). The mirror is a `conductor` without Fresnel
(material "none") scaled by 0.9 (ptsc's `reflection rgb 0.9`).
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "mitsuba"


def scene(res, spp):
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1, 4], [0, 0.4, 0], 45.0, [0, 1, 0]),
        "sky": {"type": "envmap", "filename": str(ROOT / "examples" / "images" / "studio.exr"), "scale": 0.8},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], {"type": "diffuse", "reflectance": rgb([0.5] * 3)}),
        "ball": {"type": "sphere", "center": [-0.6, 0.5, 0], "radius": 0.5,
                 "bsdf": {"type": "diffuse", "reflectance": rgb([0.8, 0.6, 0.4])}},
        "mirror": {"type": "sphere", "center": [0.6, 0.5, -0.3], "radius": 0.5,
                   "bsdf": {"type": "conductor", "material": "none", "specular_reflectance": rgb([0.9] * 3)}},
    }


def main():
    mi.set_variant("scalar_rgb")
    # Fireflies (the sun in the mirror): 32 seeds for a stable median.
    reference_and_baseline("envmap", scene, 32)


if __name__ == "__main__":
    main()
