#!/usr/bin/env python3
"""Mitsuba 3 references and noise baselines of the participating-media
scenes tests/mitsuba/media_*.pts (issue 42): Mitsuba's `volpath` with
`homogeneous` media and Henyey–Greenstein phase functions.

  python3 scripts/mitsuba_media.py SCENE [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 8]

SCENE is fog, liquid, slab or atmosphere. Writes
tests/mitsuba/media_SCENE_ref_<res>_<ref-spp>spp.exr and the scene's entry
of tests/mitsuba/baseline.json (Mitsuba's own MAE/mean at --spp).

How ptsc's scenes map onto Mitsuba's:
  `type none` + a medium  -> a shape with a `null` BSDF and an `interior`
                             `homogeneous` medium (sigma_t = absorption +
                             scattering, albedo = scattering / sigma_t per
                             channel, `hg` phase with g = anisotropy);
  glass + a medium        -> `dielectric` with the same `interior`;
  `density D medium_color C` -> sigma_t = D, albedo = C;
  `atmosphere { center radius }` -> a `null` sphere of that centre and radius
                             with the medium inside, and the sensor's `medium`
                             (the camera is in it);
  `box`                   -> a `cube` scaled and moved onto it;
  walls                   -> `twosided` diffuse (ptsc's diffuse reflects on both sides).
Mitsuba draws the hero channel once per path, ptsc at every segment; both
are unbiased. Russian roulette differs (both unbiased); max_depth counts the
same vertices (a null boundary is not one).
"""
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle, reference_and_baseline, sensor  # noqa: E402


def diffuse(v):
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(v)}}


def lamp(p0, e1, e2, radiance):
    """A one-sided emissive quad (ptsc's `diffuse rgb 0 emission …`)."""
    shape = rectangle(p0, e1, e2, {"type": "diffuse", "reflectance": rgb([0, 0, 0])})
    shape["emitter"] = {"type": "area", "radiance": rgb(radiance)}
    return shape


def homogeneous(absorption, scattering, g):
    sa, ss = np.asarray(absorption, float), np.asarray(scattering, float)
    st = sa + ss
    albedo = np.where(st > 0, ss / np.where(st > 0, st, 1), 0)
    # Mitsuba reads sigma_t as a colour within [0, 1] times `scale`.
    scale = float(st.max())
    return {"type": "homogeneous", "sigma_t": rgb((st / scale).tolist()), "scale": scale,
            "albedo": rgb(albedo.tolist()), "phase": {"type": "hg", "g": float(g)}}


def box(lo, hi, bsdf, interior=None):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    c, h = (lo + hi) / 2, (hi - lo) / 2
    shape = {"type": "cube", "to_world": mi.ScalarTransform4f().translate(c.tolist()).scale(h.tolist()),
             "bsdf": bsdf}
    if interior is not None:
        shape["interior"] = interior
    return shape


NULL = {"type": "null"}


def volpath(max_depth):
    return {"type": "volpath", "max_depth": max_depth}


def fog(res, spp):
    white = diffuse([0.8, 0.75, 0.7])
    return {
        "type": "scene",
        "integrator": volpath(16),
        "sensor": sensor(res, spp, [0, 0, 3.9], [0, 0, 0], 39.3077),
        "floor": rectangle([-1, -1, -1], [0, 0, 2], [2, 0, 0], white),
        "ceiling": rectangle([-1, 1, -1], [2, 0, 0], [0, 0, 2], white),
        "back": rectangle([-1, -1, -1], [2, 0, 0], [0, 2, 0], white),
        "left": rectangle([-1, -1, -1], [0, 2, 0], [0, 0, 2], diffuse([0.6, 0.1, 0.1])),
        "right": rectangle([1, -1, -1], [0, 0, 2], [0, 2, 0], diffuse([0.1, 0.5, 0.1])),
        "ball": {"type": "sphere", "center": [0.15, 0.1, -0.1], "radius": 0.2, "bsdf": white},
        "spot": {"type": "spot", "intensity": rgb([12, 11, 9]), "cutoff_angle": 25.0, "beam_width": 25.0,
                 "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0.9, 0], target=[0.25, -1, -0.2],
                                                            up=[0, 0, 1])},
        "fog": box([-0.95] * 3, [0.95, 0.6, 0.95], NULL, homogeneous([0.05, 0.05, 0.08], [0.6, 0.6, 0.55], 0.4)),
    }


def liquid(res, spp):
    return {
        "type": "scene",
        "integrator": volpath(32),
        "sensor": sensor(res, spp, [0, 1.2, 3.6], [0, 0.55, 0], 40.0),
        "background": {"type": "constant", "radiance": rgb([0.1] * 3)},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], diffuse([0.6] * 3)),
        "lamp": lamp([-0.5, 2.5, -0.5], [1, 0, 0], [0, 0, 1], [12] * 3),
        "liquid": {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.6,
                   "bsdf": {"type": "dielectric", "int_ior": 1.33, "ext_ior": 1.0},
                   "interior": homogeneous([0.1, 0.5, 2], [3, 2, 1], 0.5)},
    }


def slab(res, spp):
    return {
        "type": "scene",
        "integrator": volpath(256),
        "sensor": sensor(res, spp, [0, 2, 3.2], [0, 0.2, 0], 40.0),
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], diffuse([0.2] * 3)),
        "lamp": lamp([-1, 2.2, -0.2], [0.8, 0, 0], [0, 0.3, 0.8], [10] * 3),
        "slab": box([-0.8, 0.05, -0.6], [0.8, 0.45, 0.6], NULL,
                    homogeneous([10 * 0.01] * 3, [10 * 0.99] * 3, 0.0)),
    }


def atmosphere(res, spp):
    haze = homogeneous([0.01] * 3, [0.08, 0.1, 0.13], 0.7)
    camera = sensor(res, spp, [0, 1, 4], [0, 0.8, 0], 50.0)
    camera["medium"] = {"type": "ref", "id": "haze"}
    return {
        "type": "scene",
        "integrator": volpath(16),
        "haze": {**haze, "id": "haze"},
        "sensor": camera,
        "ground": rectangle([-4, 0, 4], [8, 0, 0], [0, 0, -8], diffuse([0.5] * 3)),
        "wall": rectangle([-1.5, 0, -1], [3, 0, 0], [0, 2, 0], diffuse([0.7, 0.6, 0.5])),
        "block": box([-0.4, 0, 0.2], [0.2, 1.4, 0.8], diffuse([0.7] * 3)),
        "sun": {"type": "directional", "direction": [-0.4, -0.6, -0.7], "irradiance": rgb([3, 2.8, 2.5])},
        "ball": {"type": "sphere", "center": [0, 0, 0], "radius": 6.0, "bsdf": NULL,
                 "interior": {"type": "ref", "id": "haze"}},
    }


SCENES = {"fog": fog, "liquid": liquid, "slab": slab, "atmosphere": atmosphere}


def main():
    name = sys.argv.pop(1)
    mi.set_variant("llvm_ad_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    reference_and_baseline(f"media_{name}", SCENES[name], 8)


if __name__ == "__main__":
    main()
