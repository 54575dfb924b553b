#!/usr/bin/env python3
"""Mitsuba 3's direct light from lights_textured.pts's environment map,
estimated twice (tests/mitsuba/env_direct.pts):

  python3 scripts/mitsuba_env_direct.py [--res 64] [--emitter-spp 4096] [--bsdf-spp 16384]

Writes tests/mitsuba/env_direct_emitter_<res>_<spp>spp.exr (`direct` with
emitter sampling only) and env_direct_bsdf_<res>_<spp>spp.exr (`direct`
with BSDF sampling only). Both estimate the same integral; on this map (a
small sun of radiance up to 2000 in a 64 x 32 image) Mitsuba 3.9.1's two
differ, which tests/integration/mitsuba.rs pins down.
"""
import argparse
import sys
from pathlib import Path

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
sys.path.insert(0, str(Path(__file__).resolve().parent))
import mitsuba_lights  # noqa: E402
from mitsuba_textures import OUT  # noqa: E402


def scene(res, spp, emitter, bsdf):
    d = mitsuba_lights.lights_textured(res, spp)
    for key in ["sun", "lamp", "spot", "small"]:
        del d[key]
    d["integrator"] = {"type": "direct", "emitter_samples": emitter, "bsdf_samples": bsdf}
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--emitter-spp", type=int, default=4096)
    ap.add_argument("--bsdf-spp", type=int, default=16384)
    a = ap.parse_args()
    for name, spp, emitter, bsdf in [("emitter", a.emitter_spp, 1, 0), ("bsdf", a.bsdf_spp, 0, 1)]:
        img = np.array(mi.render(mi.load_dict(scene(a.res, spp, emitter, bsdf)), spp=spp), dtype=np.float32)
        path = OUT / f"env_direct_{name}_{a.res}_{spp}spp.exr"
        mi.Bitmap(img[..., :3]).write(str(path))
        print(path.name, "mean", img[..., :3].mean())


if __name__ == "__main__":
    main()
