#!/usr/bin/env python3
"""Mitsuba 3 reference and noise baseline for tests/mitsuba/textures.pts.

  python3 scripts/mitsuba_textures.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 8]

Writes tests/mitsuba/textures_ref_<res>_<ref-spp>spp.exr (Mitsuba's `path`,
scalar_rgb) and the "textures" entry of tests/mitsuba/baseline.json (Mitsuba's
own MAE/mean at --spp over --seeds seeds), which the Rust test
`mitsuba_reference_textures` compares ptsc with.

The scene is written here by hand, the same as textures.pts, with the
conventions of scripts/../shared/bench/mitsuba_scenes.py (perspective camera
with a vertical fov, box filter, independent sampler); the textured lamp is
the only light, so that the comparison measures textures and not the choice
between lights (a sky beside the lamp is issue 22's case: ptsc's
power-proportional selection gives the sky 94 % of the shadow rays and
its MAE is 1.4 x Mitsuba's there). How ptsc's
texture coordinates map onto Mitsuba's (geometry/texcoord.rs):
  quad   -> `rectangle` with to_world columns (e1/2, e2/2, n, centre): its
            (u, v) is ptsc's (s, t) exactly;
  sphere -> Mitsuba's local frame L = (-d.z, d.x, -d.y) of ptsc's direction d
            (a rotation) gives u' = 1 - u and v' = v; a checker's cells then
            swap, so Mitsuba's color0 is ptsc's `odd`;
  checker `scale s` -> `to_uv` scale 1/s (ptsc's even = Mitsuba's color0);
  bitmap -> Mitsuba reads v = 0 at an image's top row, ptsc at its bottom
            (as pbrt and OBJ's vt; Mitsuba's OBJ loader flips v instead):
            `to_uv` maps (u, v) to (u, 1 - v) on the rectangle, and to
            (1 - u, 1 - v) on the turned sphere.
  emitter -> an `area` emitter whose radiance is a bitmap (lamp.exr, a 4 x 4
            HDR checker written here: Mitsuba's checkerboard holds
            reflectances only), on a rectangle with a black BSDF (ptsc's
            emission-only material).
  normal map -> `normalmap` around a `diffuse`, its `bitmap` read raw
            (ptsc reads images given to `normal_map` linearly); both build
            the tangent frame (dp/du made orthogonal to n, n x that) and
            decode a texel c as 2c - 1. The map (ripples_normal.png) is
            written here, tilting normals by at most 15 degrees. Where a
            bent normal would let a diffuse reflection cross the quad,
            Mitsuba follows it (the ray leaves behind the quad) and ptsc
            refuses it (Veach's rule, ptsc::integrator::crosses_surface);
            with tilts this mild the difference is below the test's
            tolerance.
"""
import argparse
import json
import statistics
from pathlib import Path

import numpy as np
import mitsuba as mi

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "mitsuba"


def rgb(v):
    return {"type": "rgb", "value": [float(x) for x in v]}


def checker(color0, color1, scale):
    return {"type": "diffuse", "reflectance": {
        "type": "checkerboard", "color0": rgb(color0), "color1": rgb(color1),
        "to_uv": mi.ScalarTransform4f().scale([1.0 / scale, 1.0 / scale, 1.0])}}


def bitmap(to_uv, wrap):
    return {"type": "diffuse", "reflectance": {
        "type": "bitmap", "filename": str(OUT / "cornell_128.png"), "wrap_mode": wrap,
        "filter_type": "bilinear", "to_uv": to_uv}}


def ripples_normal_map(path, size=64, waves=3, tilt_deg=15.0):
    """A tangent-space normal map of ripples h = sin(2 pi k u) sin(2 pi k v),
    scaled so that no normal tilts by more than `tilt_deg`, as 8-bit RGB
    ((n + 1) / 2, row 0 at the top, v = 1 - (row + 0.5) / size)."""
    c = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(c, 1.0 - c)
    k = 2 * np.pi * waves
    du = k * np.cos(k * u) * np.sin(k * v)
    dv = k * np.sin(k * u) * np.cos(k * v)
    scale = np.tan(np.radians(tilt_deg)) / np.sqrt(du ** 2 + dv ** 2).max()
    n = np.stack([-scale * du, -scale * dv, np.ones_like(u)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    texels = np.clip(np.round((n + 1) * 0.5 * 255), 0, 255).astype(np.uint8)
    mi.Bitmap(texels, pixel_format=mi.Bitmap.PixelFormat.RGB).write(str(path))


def normal_mapped(diffuse, to_uv):
    return {"type": "normalmap",
            "normalmap": {"type": "bitmap", "filename": str(OUT / "ripples_normal.png"),
                          "raw": True, "filter_type": "bilinear", "to_uv": to_uv},
            "bsdf": {"type": "diffuse", "reflectance": rgb(diffuse)}}


def lamp_image(path, even=(6, 5, 4), odd=(1, 1, 2), size=4):
    """A small HDR checker (size x size texels of two radiances) as OpenEXR."""
    y, x = np.mgrid[0:size, 0:size]
    img = np.where(((x + y) % 2 == 0)[..., None], np.array(even, np.float32), np.array(odd, np.float32))
    mi.Bitmap(img.astype(np.float32)).write(str(path))


def emitter(p0, e1, e2, to_uv):
    shape = rectangle(p0, e1, e2, {"type": "diffuse", "reflectance": rgb([0, 0, 0])})
    shape["emitter"] = {"type": "area", "radiance": {
        "type": "bitmap", "filename": str(OUT / "lamp.exr"), "filter_type": "bilinear",
        "wrap_mode": "repeat", "to_uv": to_uv}}
    return shape


def flip(su, sv):
    """(u, v) -> (u, 1 - v) for su = 1, sv = -1; (1 - u, 1 - v) for -1, -1."""
    return mi.ScalarTransform4f().translate([0.0 if su > 0 else 1.0, 1.0, 0.0]).scale([su, sv, 1.0])


def turned_sphere(centre, radius):
    """ptsc's sphere direction d = R L, R's rows (0,1,0), (0,0,-1), (-1,0,0)."""
    m = np.eye(4)
    m[:3, :3] = radius * np.array([[0, 1, 0], [0, 0, -1], [-1, 0, 0]], dtype=np.float64)
    m[:3, 3] = centre
    return mi.ScalarTransform4f(m.tolist())


def sensor(res, spp, origin, target, fov, up=(0, 1, 0)):
    """ptsc's camera: perspective with a vertical fov, box filter, RGB
    float film, independent sampler."""
    return {
        "type": "perspective", "fov": float(fov), "fov_axis": "y", "near_clip": 1e-3, "far_clip": 1e4,
        "to_world": mi.ScalarTransform4f().look_at(origin=list(origin), target=list(target), up=list(up)),
        "film": {"type": "hdrfilm", "width": res, "height": res, "pixel_format": "rgb",
                 "component_format": "float32", "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": spp},
    }


def rectangle(p0, e1, e2, bsdf):
    p0, e1, e2 = (np.asarray(x, dtype=np.float64) for x in (p0, e1, e2))
    n = np.cross(e1, e2)
    n /= np.linalg.norm(n)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = 0.5 * e1, 0.5 * e2, n, p0 + 0.5 * (e1 + e2)
    return {"type": "rectangle", "to_world": mi.ScalarTransform4f(m.tolist()), "bsdf": bsdf}


def scene(res, spp):
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": sensor(res, spp, [0, 0.3, 4], [0, -0.1, 0], 40.0, [0, 1, 0]),
        "lamp": emitter([-0.6, 1.2, 0.2], [1.2, 0, 0], [0, 0, 0.8], flip(1, -1)),
        "ripples": rectangle([0.3, 0.1, -0.9], [1.1, 0, 0], [0, 0.9, 0],
                             normal_mapped([0.7, 0.7, 0.75], flip(1, -1))),
        "wall": rectangle([-1.8, -1, -1], [3.6, 0, 0], [0, 2.2, 0],
                          checker([0.8, 0.7, 0.2], [0.1, 0.2, 0.6], 0.25)),
        "floor": rectangle([-3, -1, 3], [6, 0, 0], [0, 0, -4], checker([0.8] * 3, [0.2] * 3, 0.1)),
        "ball": {"type": "sphere", "to_world": turned_sphere([0.5, -0.35, 0.3], 0.6),
                 "bsdf": checker([0.7, 0.1, 0.1], [0.9] * 3, 0.125)},
        "poster": rectangle([-1.6, -0.2, -0.9], [1.2, 0, 0], [0, 1.2, 0], bitmap(flip(1, -1), "clamp")),
        "globe": {"type": "sphere", "to_world": turned_sphere([-0.9, -0.6, 0.8], 0.4),
                  "bsdf": bitmap(flip(-1, -1), "repeat")},
    }


def reference_and_baseline(key, scene_of, default_seeds):
    """Parses --res --ref-spp --spp --seeds, renders Mitsuba's reference of
    scene_of(res, spp) (passes of 1024 spp with distinct seeds, averaged) to
    tests/mitsuba/<key>_ref_<res>_<ref-spp>spp.exr and writes Mitsuba's own
    MAE/mean at --spp over --seeds seeds as baseline.json's <key> entry.
    Shared by the Mitsuba scripts of the test scenes."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=16384)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=default_seeds)
    a = ap.parse_args()
    ref_scene = mi.load_dict(scene_of(a.res, a.ref_spp))
    passes = max(1, a.ref_spp // 1024)
    ref = sum(np.array(mi.render(ref_scene, spp=a.ref_spp // passes, seed=10_000 + k), dtype=np.float64)
              for k in range(passes)) / passes
    name = f"{key}_ref_{a.res}_{a.ref_spp}spp.exr"
    mi.Bitmap(ref.astype(np.float32)).write(str(OUT / name))
    s = mi.load_dict(scene_of(a.res, a.spp))
    maes = []
    for seed in range(a.seeds):
        img = np.array(mi.render(s, spp=a.spp, seed=seed), dtype=np.float64)[..., :3]
        maes.append(float(np.abs(img - ref[..., :3]).mean() / ref[..., :3].mean()))
    base_path = OUT / "baseline.json"
    base = json.loads(base_path.read_text())
    base["scenes"][key] = {"reference": name, "mae_over_mean": maes,
                           "median_mae_over_mean": statistics.median(maes)}
    base_path.write_text(json.dumps(base, indent=1) + "\n")
    print(key, f"median MAE/mean {statistics.median(maes):.5f}", [round(x, 5) for x in maes])


def main():
    mi.set_variant("scalar_rgb")
    ripples_normal_map(OUT / "ripples_normal.png")
    lamp_image(OUT / "lamp.exr")
    reference_and_baseline("textures", scene, 8)


if __name__ == "__main__":
    main()
