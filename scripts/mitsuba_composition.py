#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline of tests/mitsuba/composition.pts:
open cylinders and a group placed three times (`shapegroup` + `instance`).

  python3 scripts/mitsuba_composition.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/composition_ref_<res>_<ref-spp>spp.exr and the
composition entry of tests/mitsuba/baseline.json. ptsc's diffuse reflects on
both sides; Mitsuba's only on the side its normal faces: every surface here
is `twosided`. Mitsuba's cylinder runs from p0 to p1 without caps, as ptsc's
`cylinder { … open true }`.
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402


def diffuse(v):
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(v)}}


def placement(translate, rotate=(0, 0, 0), scale=1.0):
    """ptsc's `rotate <x, y, z> scale s translate t`: scale, then x, y, z
    rotations in degrees, then the translation."""
    t = mi.ScalarTransform4f().translate(list(translate))
    for axis, angle in ((2, rotate[2]), (1, rotate[1]), (0, rotate[0])):
        a = [0, 0, 0]
        a[axis] = 1
        t = t @ mi.ScalarTransform4f().rotate(a, angle)
    return t @ mi.ScalarTransform4f().scale(scale)


def composition(res, spp):
    wall = diffuse([0.6] * 3)
    lamp = rectangle([-0.75, 3, -0.25], [1.5, 0, 0], [0, 0, 1.5], {"type": "diffuse", "reflectance": rgb([0, 0, 0])})
    lamp["emitter"] = {"type": "area", "radiance": rgb([8, 8, 8])}
    post = {
        "type": "shapegroup",
        "cylinder": {"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 1.5, 0], "radius": 0.25,
                     "bsdf": diffuse([0.7, 0.25, 0.2])},
        "ball": {"type": "sphere", "center": [0, 1.8, 0], "radius": 0.2, "bsdf": diffuse([0.2, 0.4, 0.7])},
    }

    def instance(t):
        return {"type": "instance", "shapegroup": {"type": "ref", "id": "post"}, "to_world": t}

    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1.2, 5], [0, 0.7, 0], 45.0),
        "background": {"type": "constant", "radiance": rgb([0.1] * 3)},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], wall),
        "back": rectangle([-3, 0, -2], [6, 0, 0], [0, 3, 0], wall),
        "lamp": lamp,
        "post": post,
        "a": instance(placement([-1.5, 0, 0])),
        "b": instance(placement([0, 0, -0.6], (0, 30, 0), 0.8)),
        "c": instance(placement([1.5, 0, 0.3], (0, 0, 10))),
        "log": {"type": "cylinder", "p0": [-1, 0.3, 1.2], "p1": [1, 0.3, 1.2], "radius": 0.3,
                "bsdf": diffuse([0.3, 0.7, 0.3])},
    }


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    reference_and_baseline("composition", composition, 16)


if __name__ == "__main__":
    main()
