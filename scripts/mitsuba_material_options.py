#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline for tests/mitsuba/material_options.pts.

  python3 scripts/mitsuba_material_options.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/material_options_ref_<res>_<ref-spp>spp.exr and the
"material_options" entry of tests/mitsuba/baseline.json. The scene is
written by hand, the same as material_options.pts (issue 34's "what users
tried to say"), with the conventions of mitsuba_materials.py and
mitsuba_textures.py:
  gold, its roughness a checker -> `roughconductor` whose `alpha` is a
            `checkerboard` of gloss² (on the turned sphere of
            mitsuba_textures.py, so that ptsc's (u, v) maps onto Mitsuba's,
            which swaps the cells; but Mitsuba 3.9.1's checkerboard swaps
            its colours once more when read as a number (`eval_1` gives
            color1 where `eval` gives color0: checked at three points), so
            color0 is ptsc's `even` here; a close-up of the ball: MAE/mean
            4.9 % at 256 spp, 35 % with the colours the other way);
  copper rough unevenly -> `roughconductor` with `alpha_u`, `alpha_v` (on
            the turned sphere: Mitsuba's tangent is its dp/du, along the
            parallels, as ptsc's);
  frosted glass in water -> `roughdielectric` with `int_ior` 1.5 and
            `ext_ior` 1.33;
  an air bubble in water -> `dielectric` with `int_ior` 1 and `ext_ior`
            1.33 (a relative index below 1);
  aluminium in water -> `conductor` whose eta and k are divided by 1.33
            (Mitsuba 3 has no outside index for metals);
  a ball wearing an 8-bit image read linearly -> `bitmap` with `raw`.
Rough metals here have `multiscatter false`: Mitsuba's have no
compensation.
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_materials import stage  # noqa: E402
from mitsuba_textures import OUT, flip, reference_and_baseline, rgb, turned_sphere  # noqa: E402

GOLD = ([0.143036, 0.375307, 1.44205], [3.983, 2.38556, 1.60336])
COPPER = ([0.201005, 0.92375, 1.10222], [3.91326, 2.45305, 2.14209])
ALUMINIUM = ([1.6575, 0.880405, 0.521244], [9.22381, 6.2695, 4.837])


def ball(x, z, bsdf):
    return {"type": "sphere", "to_world": turned_sphere([x, 0.5, z], 0.5), "bsdf": bsdf}


def scene(res, spp):
    # ptsc: gloss checker { even 0.2 odd 0.7 scale 0.125 } -> alpha = gloss².
    alpha = {"type": "checkerboard", "color0": rgb([0.2 ** 2] * 3), "color1": rgb([0.7 ** 2] * 3),
             "to_uv": mi.ScalarTransform4f().scale([8.0, 8.0, 1.0])}
    return {
        **stage(res, spp),
        "gold": ball(-1.2, -0.8, {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
                                  "eta": rgb(GOLD[0]), "k": rgb(GOLD[1])}),
        "copper": ball(0, -0.8, {"type": "roughconductor", "distribution": "ggx", "alpha_u": 0.05,
                                 "alpha_v": 0.4, "eta": rgb(COPPER[0]), "k": rgb(COPPER[1])}),
        "frosted": ball(1.2, -0.8, {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.09,
                                    "int_ior": 1.5, "ext_ior": 1.33}),
        "bubble": ball(-1.2, 0.6, {"type": "dielectric", "int_ior": 1.0, "ext_ior": 1.33}),
        # Mitsuba 3's conductor has no outside index: its eta and k are
        # relative, divided by the water's here.
        "aluminium": ball(0, 0.6, {"type": "conductor", "eta": rgb([e / 1.33 for e in ALUMINIUM[0]]),
                                   "k": rgb([k / 1.33 for k in ALUMINIUM[1]])}),
        "linear": ball(1.2, 0.6, {"type": "diffuse", "reflectance": {
            "type": "bitmap", "filename": str(OUT / "cornell_128.png"), "raw": True,
            "filter_type": "bilinear", "to_uv": flip(-1, -1)}}),
    }


def main():
    mi.set_variant("scalar_rgb")
    reference_and_baseline("material_options", scene, 16)


if __name__ == "__main__":
    main()
