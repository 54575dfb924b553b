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
import argparse
import json
import statistics
import sys
from pathlib import Path

import numpy as np
import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import rgb, rectangle  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "mitsuba"


def scene(res, spp):
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": {
            "type": "perspective", "fov": 45.0, "fov_axis": "y", "near_clip": 1e-3, "far_clip": 1e4,
            "to_world": mi.ScalarTransform4f().look_at(origin=[0, 1, 4], target=[0, 0.4, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": res, "height": res, "pixel_format": "rgb",
                     "component_format": "float32", "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "sky": {"type": "envmap", "filename": str(ROOT / "examples" / "images" / "studio.exr"), "scale": 0.8},
        "floor": rectangle([-3, 0, 3], [6, 0, 0], [0, 0, -6], {"type": "diffuse", "reflectance": rgb([0.5] * 3)}),
        "ball": {"type": "sphere", "center": [-0.6, 0.5, 0], "radius": 0.5,
                 "bsdf": {"type": "diffuse", "reflectance": rgb([0.8, 0.6, 0.4])}},
        "mirror": {"type": "sphere", "center": [0.6, 0.5, -0.3], "radius": 0.5,
                   "bsdf": {"type": "conductor", "material": "none", "specular_reflectance": rgb([0.9] * 3)}},
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=16384)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=32)
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    ref_scene = mi.load_dict(scene(a.res, a.ref_spp))
    passes = max(1, a.ref_spp // 1024)
    ref = sum(np.array(mi.render(ref_scene, spp=a.ref_spp // passes, seed=10_000 + k), dtype=np.float64)
              for k in range(passes)) / passes
    name = f"envmap_ref_{a.res}_{a.ref_spp}spp.exr"
    mi.Bitmap(ref.astype(np.float32)).write(str(OUT / name))
    s = mi.load_dict(scene(a.res, a.spp))
    maes = []
    for seed in range(a.seeds):
        img = np.array(mi.render(s, spp=a.spp, seed=seed), dtype=np.float64)[..., :3]
        maes.append(float(np.abs(img - ref[..., :3]).mean() / ref[..., :3].mean()))
    base_path = OUT / "baseline.json"
    base = json.loads(base_path.read_text())
    base["scenes"]["envmap"] = {"reference": name, "mae_over_mean": maes,
                                "median_mae_over_mean": statistics.median(maes)}
    base_path.write_text(json.dumps(base, indent=1) + "\n")
    print("envmap", f"median MAE/mean {statistics.median(maes):.5f}", [round(x, 5) for x in maes])


if __name__ == "__main__":
    main()
