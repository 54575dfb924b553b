#!/usr/bin/env python3
"""Writes examples/models/table.gltf (with table.bin and checker.png beside
it) and examples/models/table.glb (the same scene in one binary file): a
small table for examples/gltf.pts. It shows what ptsc reads of glTF 2.0: a
node hierarchy (a table node holding a top and four legs, a vase rotated
on the top), one leg mesh placed by four nodes (stored once), a
base-colour texture with KHR_texture_transform, a metallic material, a
clear-coated one, and an alpha-masked leaf (a cutout: the leaf image's
alpha). Nothing is downloaded; run again after a change.

    python3 scripts/make_gltf_example.py
"""
import json
import math
import struct
import zlib
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "examples" / "models"


def png(width, height, pixel):
    """An 8-bit RGB PNG of pixel(x, y) -> (r, g, b), or RGBA where it gives
    four samples."""
    colour = 6 if len(pixel(0, 0)) == 4 else 2
    rows = b"".join(
        b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height)
    )

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def box(lo, hi):
    """Positions, normals, UVs and indices of an axis-aligned box."""
    p, n, uv, idx = [], [], [], []
    faces = [
        ((1, 0, 0), (0, 1, 2)), ((-1, 0, 0), (0, 1, 2)),
        ((0, 1, 0), (1, 2, 0)), ((0, -1, 0), (1, 2, 0)),
        ((0, 0, 1), (2, 0, 1)), ((0, 0, -1), (2, 0, 1)),
    ]
    for normal, (a, b, c) in faces:
        axis = [i for i in range(3) if normal[i] != 0][0]
        side = hi[axis] if normal[axis] > 0 else lo[axis]
        u_axis, v_axis = [i for i in range(3) if i != axis]
        base = len(p)
        for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
            q = [0.0, 0.0, 0.0]
            q[axis] = side
            q[u_axis] = hi[u_axis] if du else lo[u_axis]
            q[v_axis] = hi[v_axis] if dv else lo[v_axis]
            p.append(q)
            n.append(list(normal))
            uv.append([du, 1 - dv])
        # Outward winding: (u × v) along the normal, else reversed.
        cross = [0, 0, 0]
        cross[3 - u_axis - v_axis] = 1 if (v_axis - u_axis) % 3 == 1 else -1
        outward = sum(cross[i] * normal[i] for i in range(3)) > 0
        quad = [0, 1, 2, 0, 2, 3] if outward else [0, 2, 1, 0, 3, 2]
        idx += [base + i for i in quad]
    return p, n, uv, idx


def vase(radius=0.09, height=0.3, sides=24, rings=8):
    """A lathed vase, open at the top."""
    p, n, uv, idx = [], [], [], []
    for r in range(rings + 1):
        t = r / rings
        y = height * t
        rad = radius * (0.6 + 0.6 * math.sin(math.pi * (0.15 + 0.8 * t)))
        for s in range(sides + 1):
            a = 2 * math.pi * s / sides
            p.append([rad * math.cos(a), y, rad * math.sin(a)])
            n.append([math.cos(a), 0.0, math.sin(a)])
            uv.append([s / sides, t])
    for r in range(rings):
        for s in range(sides):
            a = r * (sides + 1) + s
            b = a + sides + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return p, n, uv, idx


def leaf():
    """A square the alpha mask cuts into a leaf."""
    return ([[-0.1, 0, 0], [0.1, 0, 0], [0.1, 0.2, 0], [-0.1, 0.2, 0]],
            [[0, 0, 1]] * 4, [[0, 1], [1, 1], [1, 0], [0, 0]], [0, 1, 2, 0, 2, 3])


class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors, self.meshes = [], [], []

    def view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            view["target"] = target
        self.bin += data
        self.views.append(view)
        return len(self.views) - 1

    def accessor(self, values, kind, component=5126, target=34962):
        flat = [x for v in values for x in (v if isinstance(v, list) else [v])]
        fmt = {5126: "f", 5125: "I"}[component]
        view = self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat), target)
        acc = {"bufferView": view, "componentType": component, "count": len(values), "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(v[i] for v in values) for i in range(3)]
            acc["max"] = [max(v[i] for v in values) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def mesh(self, name, geometry, material):
        p, n, uv, idx = geometry
        attributes = {
            "POSITION": self.accessor(p, "VEC3"),
            "NORMAL": self.accessor(n, "VEC3"),
            "TEXCOORD_0": self.accessor(uv, "VEC2"),
        }
        indices = self.accessor(idx, "SCALAR", 5125, 34963)
        self.meshes.append({"name": name, "primitives": [
            {"attributes": attributes, "indices": indices, "material": material}]})
        return len(self.meshes) - 1


def leaf_texel(x, y):
    """A leaf on a 64 x 64 image: opaque inside two circular arcs meeting at
    the tip and the stem (a lens along the diagonal), with a paler midrib;
    clear outside."""
    u, v = (x + 0.5) / 64, (y + 0.5) / 64
    # Along the diagonal from the stem (0.1, 0.9) to the tip (0.9, 0.1).
    along = ((u - 0.1) - (v - 0.9)) / (2 * 0.8)
    across = ((u - 0.1) + (v - 0.9)) / 2
    half_width = 0.16 * math.sin(math.pi * min(max(along, 0.0), 1.0))
    inside = 0.0 <= along <= 1.0 and abs(across) <= half_width
    rib = abs(across) < 0.012
    colour = (150, 190, 90) if rib else (60, 140, 50)
    return colour + ((255 if inside else 0),)


def document(embed_images):
    b = Builder()
    top = b.mesh("Top", box([-0.6, 0.0, -0.4], [0.6, 0.05, 0.4]), 0)
    leg = b.mesh("Leg", box([-0.03, -0.7, -0.03], [0.03, 0.0, 0.03]), 1)
    pot = b.mesh("Vase", vase(), 2)
    leaf_mesh = b.mesh("Leaf", leaf(), 3)
    checker = png(64, 64, lambda x, y: (200, 170, 120) if (x // 8 + y // 8) % 2 else (120, 80, 45))
    leaf_png = png(64, 64, leaf_texel)
    images = []
    for name, data in (("checker.png", checker), ("leaf.png", leaf_png)):
        if embed_images:
            images.append({"bufferView": b.view(data), "mimeType": "image/png", "name": name})
        else:
            images.append({"uri": name})
            (OUT / name).write_bytes(data)
    legs = [
        {"name": "Leg %d" % k, "mesh": leg, "translation": [x, 0.0, z]}
        for k, (x, z) in enumerate([(-0.55, -0.35), (0.55, -0.35), (0.55, 0.35), (-0.55, 0.35)])
    ]
    nodes = [
        {"name": "Table", "children": [1, 2, 3, 4, 5, 6], "translation": [0, 0.7, 0],
         "rotation": [0, math.sin(math.radians(10)), 0, math.cos(math.radians(10))]},
        {"name": "Top", "mesh": top},
        *legs,
        {"name": "Vase", "mesh": pot, "translation": [0.25, 0.05, 0.05], "scale": [1.2, 1.2, 1.2],
         "children": [7]},
        {"name": "Leaf", "mesh": leaf_mesh, "translation": [0, 0.28, 0],
         "rotation": [0, 0, math.sin(math.radians(-15)), math.cos(math.radians(-15))]},
    ]
    gltf = {
        "asset": {"version": "2.0", "generator": "ptsc scripts/make_gltf_example.py"},
        "extensionsUsed": ["KHR_texture_transform", "KHR_materials_clearcoat"],
        "scene": 0,
        "scenes": [{"name": "Table", "nodes": [0]}],
        "nodes": nodes,
        "meshes": b.meshes,
        "materials": [
            {"name": "Wood", "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {
                    "KHR_texture_transform": {"scale": [2, 2], "rotation": 0.3}}},
                "metallicFactor": 0.0, "roughnessFactor": 0.45},
             "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.6,
                                                         "clearcoatRoughnessFactor": 0.1}}},
            {"name": "Steel", "pbrMetallicRoughness": {
                "baseColorFactor": [0.8, 0.8, 0.82, 1], "metallicFactor": 1.0, "roughnessFactor": 0.3}},
            {"name": "Glaze", "pbrMetallicRoughness": {
                "baseColorFactor": [0.1, 0.25, 0.6, 1], "metallicFactor": 0.0, "roughnessFactor": 0.15}},
            {"name": "Leaf", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 1},
                                      "metallicFactor": 0.0, "roughnessFactor": 0.6}},
        ],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "images": images,
        "accessors": b.accessors,
        "bufferViews": b.views,
    }
    return gltf, bytes(b.bin)


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    gltf, data = document(embed_images=False)
    gltf["buffers"] = [{"uri": "table.bin", "byteLength": len(data)}]
    (OUT / "table.bin").write_bytes(data)
    (OUT / "table.gltf").write_text(json.dumps(gltf, indent=1) + "\n")
    gltf, data = document(embed_images=True)
    gltf["buffers"] = [{"byteLength": len(data)}]
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(data), b"BIN\0") + data
    (OUT / "table.glb").write_bytes(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)


if __name__ == "__main__":
    main()
