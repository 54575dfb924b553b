#!/usr/bin/env python3
"""Mitsuba 3 references and noise baselines for the principled material's
three six-ball scenes, tests/mitsuba/principled_{a,b,c}.pts (the balls of
materials.pts's layout under the same studio map):

  a: metallic 0 at roughness 0.1 / 0.5 / 0.9; clearcoat on a half metal;
     a low specular; a tinted specular on a part metal;
  b: metallic 1 at roughness 0.1 / 0.5 / 0.9, metallic 0.5 likewise;
  c: a high tinted specular, clearcoat, sheen, glass (transmission 1),
     part glass, an anisotropic metal (on the turned sphere, whose tangent
     is ptsc's).

  python3 scripts/mitsuba_principled_scenes.py [--res 64] [--ref-spp 16384] [--spp 64] [--seeds 16] [a|b|c]

ptsc's words map to Mitsuba's as in scripts/mitsuba_principled.py.
"""
import sys
from pathlib import Path

import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_materials import stage  # noqa: E402
from mitsuba_textures import reference_and_baseline, rgb, turned_sphere  # noqa: E402

# Per scene, the six balls in materials.pts's order: (base colour, ptsc's
# parameters).
BALLS = {
    "a": [
        ([0.8, 0.2, 0.1], dict(roughness=0.1)),
        ([0.2, 0.6, 0.3], dict(roughness=0.5)),
        ([0.3, 0.3, 0.8], dict(roughness=0.9)),
        ([0.9, 0.6, 0.2], dict(roughness=0.4, metallic=0.5, clearcoat=1.0, clearcoat_roughness=0.2)),
        ([0.7, 0.7, 0.7], dict(roughness=0.3, specular=0.1)),
        ([0.8, 0.3, 0.5], dict(roughness=0.35, specular=0.8, specular_tint=1.0, metallic=0.3)),
    ],
    "b": [
        ([0.95, 0.65, 0.3], dict(roughness=0.1, metallic=1.0)),
        ([0.9, 0.9, 0.9], dict(roughness=0.5, metallic=1.0)),
        ([0.9, 0.4, 0.3], dict(roughness=0.9, metallic=1.0)),
        ([0.6, 0.3, 0.9], dict(roughness=0.1, metallic=0.5)),
        ([0.3, 0.8, 0.8], dict(roughness=0.5, metallic=0.5)),
        ([0.8, 0.8, 0.3], dict(roughness=0.9, metallic=0.5)),
    ],
    "c": [
        ([0.2, 0.4, 0.7], dict(roughness=0.3, specular=0.9, specular_tint=0.5)),
        ([0.7, 0.1, 0.1], dict(roughness=0.6, clearcoat=1.0, clearcoat_roughness=0.1)),
        ([0.2, 0.5, 0.2], dict(roughness=0.7, sheen=1.0, sheen_tint=0.5)),
        ([1.0, 1.0, 1.0], dict(roughness=0.2, transmission=1.0)),
        ([0.9, 0.7, 0.5], dict(roughness=0.5, transmission=0.6, metallic=0.2)),
        ([0.8, 0.8, 0.85], dict(roughness=0.4, metallic=0.8, anisotropic=0.7)),
    ],
}
PLACES = [(-1.2, -0.8), (0, -0.8), (1.2, -0.8), (-1.2, 0.6), (0, 0.6), (1.2, 0.6)]


def bsdf(base, params):
    p = {"type": "principled", "base_color": rgb(base)}
    for key, value in params.items():
        key = {"transmission": "spec_trans", "specular_tint": "spec_tint"}.get(key, key)
        if key == "clearcoat_roughness":
            key, value = "clearcoat_gloss", 1.0 - value
        p[key] = value
    return p


def scene_of(name):
    def scene(res, spp):
        out = stage(res, spp)
        for k, ((x, z), (base, params)) in enumerate(zip(PLACES, BALLS[name])):
            out[f"ball{k}"] = {"type": "sphere", "to_world": turned_sphere([x, 0.5, z], 0.5),
                               "bsdf": bsdf(base, params)}
        return out
    return scene


def pts(name):
    """ptsc's scene of the same balls."""
    lines = [
        f"// The principled material against Mitsuba 3's `principled`, scene {name}: written",
        "// by scripts/mitsuba_principled_scenes.py, which renders the reference.",
        "render { resolution <64, 64> samples 64 max_depth 8 }",
        "camera { position <0, 2.2, 5> look_at <0, 0.5, 0> fov 40 }",
        'environment { file "../../examples/images/studio.exr" intensity rgb 0.8 }',
        "quad { corner <-4, 0, 3> edge1 <8, 0, 0> edge2 <0, 0, -7> material { diffuse rgb 0.5 } }",
    ]
    for (x, z), (base, params) in zip(PLACES, BALLS[name]):
        words = " ".join(f"{k} {v:g}" for k, v in params.items())
        colour = ", ".join(f"{c:g}" for c in base)
        lines.append(f"sphere {{ center <{x:g}, 0.5, {z:g}> radius 0.5 material {{ type principled "
                     f"base_color rgb <{colour}> {words} }} }}")
    return "\n".join(lines) + "\n"


def main():
    names = [a for a in sys.argv[1:] if a in BALLS] or list(BALLS)
    sys.argv = [a for a in sys.argv if a not in BALLS]
    mi.set_variant("scalar_rgb")
    root = Path(__file__).resolve().parent.parent
    for name in names:
        (root / "tests" / "mitsuba" / f"principled_{name}.pts").write_text(pts(name))
        reference_and_baseline(f"principled_{name}", scene_of(name), 16)


if __name__ == "__main__":
    main()
