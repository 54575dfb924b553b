#!/usr/bin/env python3
"""Mitsuba 3 references for normal and bump maps on quads and on a mesh.

  python3 scripts/mitsuba_bumps.py SCENE [--res 64] [--ref-spp 4096] [--spp 64] [--seeds 8]

SCENE is bumps_05, bumps_1, bumps_8 (quads whose edges are 0.5, 1 or 8
long) or bump_mesh. Writes the maps (bump_normal.exr, bump_height.exr), the
scene (tests/mitsuba/SCENE.pts, and bump_mesh.obj), Mitsuba's reference
tests/mitsuba/SCENE_ref_<res>_<ref-spp>spp.exr and the SCENE entry of
tests/mitsuba/baseline.json; `mitsuba_reference_bumps_*` in
tests/integration/mitsuba.rs compares ptsc with them.

The quad scenes hold eight quads facing the camera: in four columns the
quad turned by 0, 90, 180 and 270 degrees in its plane (edge1 along +x, +y,
-x, -y), the top row normal-mapped (Mitsuba's `normalmap`), the bottom row
bump-mapped (`bumpmap`, `scale` = ptsc's `bump_height`). The camera stands
back in proportion to the edge, so the three scenes frame alike: the normal
map, read in (u, v), looks the same in all three; a bump of the same height
tilts the normal 16 times less on quads 8 long than on quads 0.5 long. A
renderer that lays the maps along a fixed basis instead of the quad's edges,
or that forgets the edges' lengths, fails all three.

bump_mesh is a curved patch (smooth vertex normals, texture coordinates
turned 30 degrees against its edges) placed twice under one rotation and an
uneven scale, normal-mapped on the left and bump-mapped on the right.

A square lamp lights every scene (see `TOWARDS_LAMP`), with a plain wall
behind the quads. Conventions as in
mitsuba_textures.py: Mitsuba's bitmap reads v = 0 at the image's top row,
ptsc at its bottom row, so the quads' bitmaps take to_uv (u, 1 - v) (their
gradient follows through the transform); Mitsuba's OBJ loader flips v
itself.
"""
import math
import sys
from pathlib import Path

import numpy as np
import mitsuba as mi

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mitsuba_textures import OUT, flip, rectangle, reference_and_baseline, rgb, sensor  # noqa: E402

# The lamp: a square facing the scene's centre from the upper left front,
# `LAMP_DISTANCE` sizes away (in units of the scene's size), about as bright
# there as a directional light of irradiance 3. An area light rather than a
# directional one: its sampling noise, not the renderers' last 0.2 % of
# shading (Mitsuba's normal-mapped diffuse reads 0.16 % below the exact
# ρ/π E cos on a constant map; ptsc within 0.01 %), sets the comparison's
# noise floor.
TOWARDS_LAMP = np.array([-0.35, 0.4, 0.85]) / np.linalg.norm([-0.35, 0.4, 0.85])
LAMP_DISTANCE = 6.0
LAMP_SIZE = 2.0
LAMP_RADIANCE = 27.0
BUMP_HEIGHT = 0.15
SIZE = 32


def texel_grid():
    """(u, v) at the texel centres, row 0 at the top (v near 1)."""
    c = (np.arange(SIZE) + 0.5) / SIZE
    return np.meshgrid(c, 1.0 - c)


def write_maps():
    """The tangent-space normal map (tilts towards +u and -v that vary with
    v and u: no turn of the frame leaves it alike) and the height map."""
    u, v = texel_grid()
    n = np.stack([0.30 + 0.15 * np.sin(2 * np.pi * v), -0.2 + 0.25 * u, np.ones_like(u)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    mi.Bitmap(((n + 1) * 0.5).astype(np.float32)).write(str(OUT / "bump_normal.exr"))
    h = 0.3 + 0.6 * u * u + 0.25 * np.sin(2 * np.pi * v) * (0.5 + 0.5 * u)
    mi.Bitmap(np.repeat(h[..., None], 3, axis=-1).astype(np.float32)).write(str(OUT / "bump_height.exr"))


def bitmap(name, to_uv):
    return {"type": "bitmap", "filename": str(OUT / name), "raw": True, "filter_type": "bilinear",
            "wrap_mode": "clamp", "to_uv": to_uv}


def diffuse():
    return {"type": "diffuse", "reflectance": rgb([0.7, 0.7, 0.7])}


def normal_mapped(to_uv):
    return {"type": "normalmap", "normalmap": bitmap("bump_normal.exr", to_uv), "bsdf": diffuse()}


def bump_mapped(to_uv):
    return {"type": "bumpmap", "height": bitmap("bump_height.exr", to_uv), "scale": BUMP_HEIGHT,
            "bsdf": diffuse()}


def lamp(scale):
    """(corner, edge1, edge2) of the lamp for a scene of size `scale`,
    edge1 × edge2 towards the scene."""
    w = -TOWARDS_LAMP
    x = np.cross(w, [0.0, 1.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(w, x)
    e1, e2 = LAMP_SIZE * scale * x, LAMP_SIZE * scale * y
    centre = LAMP_DISTANCE * scale * TOWARDS_LAMP
    assert np.dot(np.cross(e1, e2), w) > 0
    return centre - 0.5 * (e1 + e2), e1, e2


def mitsuba_lamp(scale):
    shape = rectangle(*lamp(scale), {"type": "diffuse", "reflectance": rgb([0, 0, 0])})
    shape["emitter"] = {"type": "area", "radiance": rgb([LAMP_RADIANCE] * 3)}
    return shape


def pts_vector(p):
    return f"<{p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g}>"


def pts_lamp(scale):
    c, e1, e2 = lamp(scale)
    return (f"quad {{ corner {pts_vector(c)} edge1 {pts_vector(e1)} edge2 {pts_vector(e2)}\n"
            f"       material {{ diffuse rgb 0 emission rgb {LAMP_RADIANCE} }} }}\n")


PTS_MATERIALS = (
    'material normal_mapped { diffuse rgb 0.7 normal_map image { file "bump_normal.exr" wrap clamp } }\n'
    f'material bump_mapped {{ diffuse rgb 0.7 bump image {{ file "bump_height.exr" wrap clamp }} '
    f'bump_height {BUMP_HEIGHT} }}\n'
)


def pts_head(comment, eye, target, scale):
    return (
        f"{comment}"
        "// Written by scripts/mitsuba_bumps.py (with Mitsuba's scene and reference).\n"
        "render { resolution <64, 64> samples 64 max_depth 2 }\n"
        f"camera {{ position {pts_vector(eye)} look_at {pts_vector(target)} fov 40 }}\n"
        + pts_lamp(scale) + PTS_MATERIALS
    )


def quads(edge):
    """(corner, edge1, edge2, material) of the eight quads of edge `edge`."""
    out = []
    for col in range(4):
        a = col * math.pi / 2
        e1 = edge * np.array([round(math.cos(a)), round(math.sin(a)), 0.0])
        e2 = edge * np.array([-round(math.sin(a)), round(math.cos(a)), 0.0])
        for row, material in enumerate(["normal_mapped", "bump_mapped"]):
            centre = edge * np.array([(col - 1.5) * 1.05, (0.5 - row) * 1.05, 0.0])
            out.append((centre - 0.5 * (e1 + e2), e1, e2, material))
    return out


def backdrop(edge):
    """(corner, edge1, edge2) of a plain wall just behind the quads, as
    bright as they are: their edges, where the pixels' coverage is noisy,
    then show little contrast."""
    return (edge * np.array([-4.0, -4.0, -0.002]), edge * np.array([8.0, 0, 0]), edge * np.array([0, 8.0, 0]))


def quad_scene(edge):
    eye = [0.0, 0.0, 6.0 * edge]

    def of(res, spp):
        scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 2},
                 "sensor": sensor(res, spp, eye, [0, 0, 0], 40.0), "lamp": mitsuba_lamp(edge)}
        for i, (c, e1, e2, material) in enumerate(quads(edge)):
            bsdf = normal_mapped(flip(1, -1)) if material == "normal_mapped" else bump_mapped(flip(1, -1))
            scene[f"quad{i}"] = rectangle(c, e1, e2, bsdf)
        scene["backdrop"] = rectangle(*backdrop(edge), diffuse())
        return scene

    def pts():
        text = pts_head(
            f"// Normal maps (top row) and bump maps (bottom row) on quads of edge {edge},\n"
            "// turned by 0, 90, 180 and 270 degrees in their plane, against Mitsuba 3.\n",
            eye, [0, 0, 0], edge)
        fmt = pts_vector
        for c, e1, e2, material in quads(edge):
            text += f"quad {{ corner {fmt(c)} edge1 {fmt(e1)} edge2 {fmt(e2)} material {material} }}\n"
        c, e1, e2 = backdrop(edge)
        text += f"quad {{ corner {fmt(c)} edge1 {fmt(e1)} edge2 {fmt(e2)} material {{ diffuse rgb 0.7 }} }}\n"
        return text

    return of, pts


# The mesh: a curved patch over [-1, 1]², texture coordinates turned 30°.
MESH_CELLS = 6
MESH_PLACEMENTS = [("normal_mapped", -1.15), ("bump_mapped", 1.15)]
MESH_SCALE = [1.0, 0.6, 1.3]
MESH_ROTATE = [-25.0, 30.0, 15.0]
# A wall behind the patches: the renderers' estimates of a pixel's coverage
# differ (Mitsuba's box filter spreads a sample across a pixel's border,
# ptsc's does not: 7 % less error on a lone bright quad's edges), so edges
# against black would weigh more than the maps.
MESH_BACKDROP = (np.array([-6.0, -6.0, -2.0]), np.array([12.0, 0, 0]), np.array([0, 12.0, 0]))


def mesh_obj():
    k = MESH_CELLS
    lines = []
    c30, s30 = math.cos(math.radians(30)), math.sin(math.radians(30))
    for j in range(k + 1):
        for i in range(k + 1):
            x, y = -1 + 2 * i / k, -1 + 2 * j / k
            z = 0.2 * math.sin(1.5 * x) * math.cos(y)
            dzdx = 0.3 * math.cos(1.5 * x) * math.cos(y)
            dzdy = -0.2 * math.sin(1.5 * x) * math.sin(y)
            n = np.array([-dzdx, -dzdy, 1.0])
            n /= np.linalg.norm(n)
            u, v = 0.5 + 0.4 * (c30 * x - s30 * y), 0.5 + 0.4 * (s30 * x + c30 * y)
            lines.append(f"v {x:.6f} {y:.6f} {z:.6f}")
            lines.append(f"vt {u:.6f} {v:.6f}")
            lines.append(f"vn {n[0]:.6f} {n[1]:.6f} {n[2]:.6f}")
    for j in range(k):
        for i in range(k):
            a = j * (k + 1) + i + 1
            b, c, d = a + 1, a + k + 2, a + k + 1
            for tri in ((a, b, c), (a, c, d)):
                lines.append("f " + " ".join(f"{q}/{q}/{q}" for q in tri))
    (OUT / "bump_mesh.obj").write_text("\n".join(lines) + "\n")


def mesh_to_world(dx):
    """ptsc's `scale S rotate R translate <dx, 0, 0>`: R = Rz Ry Rx."""
    ax, ay, az = (math.radians(a) for a in MESH_ROTATE)
    rx = np.array([[1, 0, 0], [0, math.cos(ax), -math.sin(ax)], [0, math.sin(ax), math.cos(ax)]])
    ry = np.array([[math.cos(ay), 0, math.sin(ay)], [0, 1, 0], [-math.sin(ay), 0, math.cos(ay)]])
    rz = np.array([[math.cos(az), -math.sin(az), 0], [math.sin(az), math.cos(az), 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rz @ ry @ rx @ np.diag(MESH_SCALE)
    m[:3, 3] = [dx, 0, 0]
    return mi.ScalarTransform4f(m.tolist())


def mesh_scene():
    eye = [0.0, 0.3, 7.5]

    def of(res, spp):
        scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 2},
                 "sensor": sensor(res, spp, eye, [0, 0, 0], 40.0), "lamp": mitsuba_lamp(1.0)}
        scene["backdrop"] = rectangle(*MESH_BACKDROP, diffuse())
        identity = mi.ScalarTransform4f()
        for material, dx in MESH_PLACEMENTS:
            bsdf = normal_mapped(identity) if material == "normal_mapped" else bump_mapped(identity)
            scene[material] = {"type": "obj", "filename": str(OUT / "bump_mesh.obj"),
                               "to_world": mesh_to_world(dx), "bsdf": bsdf}
        return scene

    def pts():
        text = pts_head(
            "// A normal map (left) and a bump map (right) on a curved, smooth-shaded mesh\n"
            "// whose texture coordinates run at 30 degrees to its edges, turned and\n"
            "// scaled unevenly, against Mitsuba 3.\n",
            eye, [0, 0, 0], 1.0)
        c, e1, e2 = MESH_BACKDROP
        text += (f"quad {{ corner {pts_vector(c)} edge1 {pts_vector(e1)} edge2 {pts_vector(e2)} "
                 "material { diffuse rgb 0.7 } }\n")
        s, r = MESH_SCALE, MESH_ROTATE
        for material, dx in MESH_PLACEMENTS:
            text += (f'mesh {{ file "bump_mesh.obj" smooth true material {material}\n'
                     f"       scale <{s[0]}, {s[1]}, {s[2]}> rotate <{r[0]}, {r[1]}, {r[2]}> translate <{dx}, 0, 0> }}\n")
        return text

    return of, pts


SCENES = {"bumps_05": lambda: quad_scene(0.5), "bumps_1": lambda: quad_scene(1.0),
          "bumps_8": lambda: quad_scene(8.0), "bump_mesh": mesh_scene}


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    name = sys.argv.pop(1)
    write_maps()
    mesh_obj()
    of, pts = SCENES[name]()
    (OUT / f"{name}.pts").write_text(pts())
    reference_and_baseline(name, of, 8)


if __name__ == "__main__":
    main()
