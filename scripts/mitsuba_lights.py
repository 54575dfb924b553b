#!/usr/bin/env python3
"""Mitsuba 3 references and noise baselines for the light-selection scenes
tests/mitsuba/lights_mixed.pts, lamp_and_sky.pts, area_sizes.pts and
lights_textured.pts (which also writes its lamp's image, hotspot_lamp.exr).

  python3 scripts/mitsuba_lights.py SCENE [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16]

Writes tests/mitsuba/SCENE_ref_<res>_<ref-spp>spp.exr and the SCENE entry of
tests/mitsuba/baseline.json. Each scene is written by hand, the same as its
.pts. Mitsuba 3 chooses lights uniformly: its noise at equal spp is the bar
ptsc's light selection must meet. lamp_and_sky is z-up (Mitsuba's `sunsky`):
ptsc's (x, y, z) is Mitsuba's (x, -z, y) there, as in mitsuba_sky.py.
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_sky import m, sun_direction  # noqa: E402
from mitsuba_textures import OUT, rgb, rectangle, reference_and_baseline, sensor  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def diffuse(v):
    return {"type": "diffuse", "reflectance": rgb(v)}


def lamp(p0, e1, e2, radiance):
    """A one-sided emissive quad (ptsc's `diffuse rgb 0 emission …`)."""
    shape = rectangle(p0, e1, e2, diffuse([0, 0, 0]))
    shape["emitter"] = {"type": "area", "radiance": rgb(radiance)}
    return shape


def lights_mixed(res, spp):
    grey = diffuse([0.6] * 3)
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1.5, 5], [0, 0.6, 0], 45.0),
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], grey),
        "back": rectangle([-3, 0, -2], [6, 0, 0], [0, 3, 0], grey),
        "left": rectangle([-2, 0, 3], [0, 0, -5], [0, 3, 0], diffuse([0.7, 0.3, 0.2])),
        "ball": {"type": "sphere", "center": [0.4, 0.5, 0], "radius": 0.5, "bsdf": diffuse([0.7] * 3)},
        "point": {"type": "point", "position": [-1.2, 2, 1], "intensity": rgb([2] * 3)},
        # beam_width = cutoff_angle: a hard cone, as ptsc's hotspot = angle.
        "spot": {"type": "spot", "intensity": rgb([30, 26, 20]), "cutoff_angle": 18.0, "beam_width": 18.0,
                 "to_world": mi.ScalarTransform4f().look_at(origin=[1.3, 2.6, -0.8], target=[1.5, 0, -1],
                                                            up=[0, 0, 1])},
        "sun": {"type": "directional", "direction": [0.5, -1, -0.4], "irradiance": rgb([0.5, 0.55, 0.7])},
    }


def lamp_and_sky(res, spp):
    sun = sun_direction(4, 40)
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, m([0, 1.2, 4.5]), m([0, 0.7, 0]), 45.0, m([0, 1, 0])),
        "sky": {"type": "sunsky", "sun_direction": m(sun), "turbidity": 3.0, "albedo": 0.3,
                "sky_scale": 0.05, "sun_scale": 0.05},
        "ground": rectangle(m([-4, 0, 4]), m([8, 0, 0]), m([0, 0, -8]), diffuse([0.5] * 3)),
        "roof": rectangle(m([-1.5, 2, 1]), m([0, 0, -2.5]), m([3, 0, 0]), diffuse([0.6] * 3)),
        "wall": rectangle(m([-1.5, 0, -1.5]), m([3, 0, 0]), m([0, 2, 0]), diffuse([0.6] * 3)),
        "ball": {"type": "sphere", "center": m([-0.4, 0.45, -0.3]), "radius": 0.45, "bsdf": diffuse([0.8] * 3)},
        "lamp": lamp(m([0.4, 1.95, -0.2]), m([0.15, 0, 0]), m([0, 0, 0.15]), [40, 32, 20]),
    }


def area_sizes(res, spp):
    grey = diffuse([0.6] * 3)
    tiny = {"type": "sphere", "center": [-1, 0.25, 0.8], "radius": 0.03, "bsdf": diffuse([0, 0, 0]),
            "emitter": {"type": "area", "radiance": rgb([900, 800, 1000])}}
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1.4, 4.5], [0, 0.6, 0], 45.0),
        "background": {"type": "constant", "radiance": rgb([0.05, 0.06, 0.08])},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], grey),
        "wall": rectangle([-3, 0, -1.5], [6, 0, 0], [0, 3, 0], grey),
        "ball": {"type": "sphere", "center": [0.6, 0.4, 0.2], "radius": 0.4, "bsdf": diffuse([0.7] * 3)},
        "panel": lamp([-2.5, 2.5, -1.4], [2, 0, 0], [0, 0, 2], [0.6] * 3),
        "medium": lamp([0.5, 2, -0.5], [0.5, 0, 0], [0, 0, 0.5], [6, 5, 4]),
        "small": lamp([1.6, 1.2, 0.5], [0.1, 0, 0], [0, 0, 0.1], [150, 120, 100]),
        "tiny": tiny,
    }


def hotspot_lamp_image(path, size=16, base=2.0, hot=100.0):
    """A lamp's radiance: `base` everywhere but a 2 x 2 hot spot of `hot`
    off centre (mean 3.5, brightest 100: a light weighed by its brightest
    texel looks 28 times brighter than it is)."""
    import numpy as np
    img = np.full((size, size, 3), base, np.float32)
    img[4:6, 10:12] = hot
    mi.Bitmap(img).write(str(path))


def lights_textured(res, spp):
    """A textured lamp with a hot spot, a dim environment map, a sun and two
    small lamps: the light-selection case of issue 34."""
    from mitsuba_textures import flip
    grey = diffuse([0.6] * 3)
    lamp_shape = rectangle([-0.4, 2.2, -0.6], [0.8, 0, 0], [0, 0, 0.8], diffuse([0, 0, 0]))
    lamp_shape["emitter"] = {"type": "area", "radiance": {
        "type": "bitmap", "filename": str(OUT / "hotspot_lamp.exr"), "filter_type": "bilinear",
        "wrap_mode": "repeat", "to_uv": flip(1, -1)}}
    small = {"type": "sphere", "center": [1.3, 0.3, 0.6], "radius": 0.05, "bsdf": diffuse([0, 0, 0]),
             "emitter": {"type": "area", "radiance": rgb([80, 70, 60])}}
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 1.4, 4.5], [0, 0.7, 0], 45.0),
        "sky": {"type": "envmap", "filename": str(ROOT / "examples" / "images" / "studio.exr"), "scale": 0.05},
        "sun": {"type": "directional", "direction": [0.4, -0.6, -0.7], "irradiance": rgb([1.0, 0.95, 0.85])},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], grey),
        "wall": rectangle([-3, 0, -1.5], [6, 0, 0], [0, 3, 0], grey),
        "ball": {"type": "sphere", "center": [-0.6, 0.45, 0.1], "radius": 0.45, "bsdf": diffuse([0.7] * 3)},
        "lamp": lamp_shape,
        "spot": lamp([0.9, 1.2, -1.0], [0.1, 0, 0], [0, 0, 0.1], [120, 100, 80]),
        "small": small,
    }


SCENES = {"lights_mixed": lights_mixed, "lamp_and_sky": lamp_and_sky, "area_sizes": area_sizes,
          "lights_textured": lights_textured}


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    name = sys.argv.pop(1)
    if name == "lights_textured":
        hotspot_lamp_image(OUT / "hotspot_lamp.exr")
    reference_and_baseline(name, SCENES[name], 16)


if __name__ == "__main__":
    main()
