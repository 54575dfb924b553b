#!/usr/bin/env python3
"""How many samples adaptive sampling saves at equal error.

Renders SCENE uniformly at a ladder of samples per pixel and adaptively at a
ladder of noise thresholds (each with a few seeds), measures each image's
error against a high-spp uniform reference, and for each threshold finds the
uniform spp of the same error (interpolated in log-log between the rungs,
where error falls as 1/spp). Prints one table per error measure:

  relMSE  mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)
  MSE     mean of (x - r)^2

    python3 scripts/adaptive_savings.py PTSC SCENE [--size 128] [--ref 8192]

Needs numpy. Renders to PFM in a temporary folder.
"""
import argparse
import math
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]


def render(ptsc, scene, out, size, spp, seed, noise=None):
    args = [ptsc, "render", scene, "-o", out, "--resolution", f"{size}x{size}",
            "--spp", str(spp), "--seed", str(seed), "--force"]
    args += ["--noise", "off" if noise is None else str(noise)]
    line = subprocess.run(args, capture_output=True, text=True, check=True).stderr.strip().splitlines()[-1]
    mean = re.search(r"([\d.]+) on average", line)
    return read_pfm(out), float(mean.group(1)) if mean else float(spp)


def errors(img, ref):
    d2 = (img - ref) ** 2
    return {"relMSE": float(np.mean(d2 / (ref ** 2 + 1e-2))), "MSE": float(np.mean(d2))}


def equal_error_spp(ladder, error):
    """The uniform spp whose error is `error`, in log-log between rungs."""
    pts = sorted(ladder)
    for (n0, e0), (n1, e1) in zip(pts, pts[1:]):
        if e1 <= error <= e0:
            t = (math.log(e0) - math.log(error)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0)))
    # Beyond the ladder: error ~ 1/spp from the nearest rung.
    n, e = pts[0] if error > pts[0][1] else pts[-1]
    return n * e / error


def main():
    p = argparse.ArgumentParser()
    p.add_argument("ptsc")
    p.add_argument("scene")
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--ref", type=int, default=8192)
    p.add_argument("--seeds", type=int, default=2)
    p.add_argument("--uniform", default="16,32,64,128,256,512")
    p.add_argument("--thresholds", default="0.1,0.05,0.03,0.02,0.01")
    p.add_argument("--cap", type=int, default=1024, help="samples at most with adaptive sampling")
    a = p.parse_args()
    tmp = Path(tempfile.mkdtemp())
    out = str(tmp / "x.pfm")
    ref, _ = render(a.ptsc, a.scene, out, a.size, a.ref, 1000)
    measures = ("relMSE", "MSE")
    ladder = {m: [] for m in measures}
    for spp in map(int, a.uniform.split(",")):
        errs = [errors(render(a.ptsc, a.scene, out, a.size, spp, s)[0], ref) for s in range(a.seeds)]
        for m in measures:
            ladder[m].append((spp, float(np.mean([e[m] for e in errs]))))
    rows = []
    for t in map(float, a.thresholds.split(",")):
        runs = [render(a.ptsc, a.scene, out, a.size, a.cap, s, noise=t) for s in range(a.seeds)]
        mean_spp = float(np.mean([r[1] for r in runs]))
        errs = [errors(r[0], ref) for r in runs]
        rows.append((t, mean_spp, {m: float(np.mean([e[m] for e in errs])) for m in measures}))
    print(f"{a.scene}, {a.size}², reference {a.ref} spp, {a.seeds} seeds; adaptive min_samples as the scene, at most {a.cap} spp")
    for m in measures:
        print(f"\n{m}: uniform " + ", ".join(f"{n} spp {e:.3g}" for n, e in ladder[m]))
        print("| threshold | mean spp | error | uniform spp of that error | samples saved |")
        print("|---|---|---|---|---|")
        for t, spp, e in rows:
            n = equal_error_spp(ladder[m], e[m])
            print(f"| {t} | {spp:.1f} | {e[m]:.3g} | {n:.1f} | {100 * (1 - spp / n):.0f} % |")


if __name__ == "__main__":
    main()
