#!/usr/bin/env python3
"""Writes examples/models/stool.obj and stool.mtl: a small stool of three
materials (a wooden seat, brushed metal legs, a red cushion), for
examples/obj_materials.pts. Nothing is downloaded; run again after a change.

    python3 scripts/make_obj_example.py
"""
import math
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "examples" / "models"

MTL = """# Three materials in the MTL keys ptsc maps to `type principled`.
newmtl Wood
Kd 0.45 0.28 0.14
Ks 0.5 0.5 0.5
Ns 60

newmtl BrushedMetal
Kd 0.85 0.85 0.88
Pm 1
Pr 0.35
aniso 0.6

newmtl Cushion
Kd 0.65 0.08 0.06
Ns 8
Ps 0.8
"""


class Obj:
    def __init__(self):
        self.v, self.lines = [], []

    def box(self, lo, hi):
        """An axis-aligned box, outward faces."""
        base = len(self.v) + 1
        for z in (lo[2], hi[2]):
            for y in (lo[1], hi[1]):
                for x in (lo[0], hi[0]):
                    self.v.append((x, y, z))
        quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        for q in quads:
            self.lines.append("f " + " ".join(str(base + i) for i in q))

    def cylinder(self, centre, radius, y0, y1, n=24):
        """A closed cylinder along y."""
        base = len(self.v) + 1
        for y in (y0, y1):
            for k in range(n):
                a = 2 * math.pi * k / n
                self.v.append((centre[0] + radius * math.cos(a), y, centre[1] + radius * math.sin(a)))
        for k in range(n):
            a, b = base + k, base + (k + 1) % n
            self.lines.append(f"f {a} {b + n} {a + n}")
            self.lines.append(f"f {a} {b} {b + n}")
        self.lines.append("f " + " ".join(str(base + k) for k in range(n)))
        self.lines.append("f " + " ".join(str(base + n + k) for k in reversed(range(n))))


def main():
    obj = Obj()
    obj.lines.append("usemtl BrushedMetal")
    for x in (-0.35, 0.35):
        for z in (-0.35, 0.35):
            obj.cylinder((x, z), 0.04, 0.0, 0.6)
    obj.lines.append("usemtl Wood")
    obj.box((-0.5, 0.6, -0.5), (0.5, 0.68, 0.5))
    obj.lines.append("usemtl Cushion")
    obj.cylinder((0.0, 0.0), 0.4, 0.68, 0.78, n=48)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "stool.mtl").write_text(MTL)
    text = ["# A stool of three materials, by scripts/make_obj_example.py.", "mtllib stool.mtl"]
    text += [f"v {x:.6g} {y:.6g} {z:.6g}" for x, y, z in obj.v]
    text += obj.lines
    (OUT / "stool.obj").write_text("\n".join(text) + "\n")
    print("wrote", OUT / "stool.obj", len(obj.v), "vertices")


if __name__ == "__main__":
    main()
