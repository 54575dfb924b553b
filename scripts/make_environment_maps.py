#!/usr/bin/env python3
"""Writes the small HDR environment maps the examples and tests read
(equirectangular, linear RGB, OpenEXR), computed here from formulas; nothing
is downloaded. Needs numpy and mitsuba (for its EXR writer).

  python3 scripts/make_environment_maps.py

examples/images/studio.exr (64 x 32): a dim blue-grey sky brightening to a
warm horizon, a dark floor below it, and a small hot spot (a "sun" of
radiance 2000 over about 3 x 2 texels) 30 degrees above the horizon, 60
degrees to the right of straight ahead: most of the light comes from a few
texels, where importance sampling matters.
"""
from pathlib import Path

import numpy as np
import mitsuba as mi

ROOT = Path(__file__).resolve().parent.parent


def studio(width=64, height=32):
    # Texel (i, j) is the direction at u = i / width, v = j / (height - 1)
    # (ptsc's and Mitsuba's envmap convention: u from straight ahead (-z)
    # towards +x, v from the zenith).
    u = np.arange(width) / width
    v = np.arange(height) / (height - 1)
    uu, vv = np.meshgrid(u, v)
    theta, phi = vv * np.pi, uu * 2 * np.pi
    d = np.stack([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)], -1)
    up = d[..., 1]
    sky = np.where(up[..., None] > 0,
                   np.array([0.25, 0.3, 0.45]) * (0.4 + 0.6 * up[..., None]) + np.array([0.35, 0.25, 0.15]) * (1 - up[..., None]) ** 4,
                   np.array([0.08, 0.07, 0.06]))
    sun_dir = np.array([np.sin(np.radians(60)) * np.cos(np.radians(30)), np.sin(np.radians(30)),
                        -np.cos(np.radians(60)) * np.cos(np.radians(30))])
    cos = d @ sun_dir
    sun = np.where(cos > np.cos(np.radians(7)), 1.0, 0.0)[..., None] * np.array([2000.0, 1800.0, 1500.0])
    return (sky + sun).astype(np.float32)


def main():
    mi.set_variant("scalar_rgb")
    out = ROOT / "examples" / "images" / "studio.exr"
    img = studio()
    mi.Bitmap(img).write(str(out))
    print(out, img.shape, "max", img.max(), "mean", img.mean())


if __name__ == "__main__":
    main()
