#!/usr/bin/env python3
"""What a per-pixel sample allocation estimated from the renders could win.

Renders SCENE uniformly with SEEDS seeds at SPP each (independent sampling,
so that a pixel's variance times its samples is its per-sample variance),
and once at REF_SPP for each pixel's mean r (a separate render, so that a
pixel's firefly does not both raise its own weight and hide its own
variance). Each pixel's per-sample variance is weighted as relMSE weighs
it (over r^2 + 0.01). The relMSE-optimal allocation at a fixed total of
samples gives pixel i a share proportional to sigma_i / sqrt(r_i^2 + 0.01)
(Lagrange: minimise sum s_i^2 / n_i with sum n_i fixed). The true sigma_i
is an oracle no renderer has, and estimating it from the samples that are
then scored flatters the allocation (a pixel that drew a firefly is both
given more samples and scored by that firefly). So the allocation is
estimated from one half of the seeds and scored on the other (and the
other way round): what an adaptive sampler that saw half of these renders'
samples would win over uniform sampling. It is not a bound on every
allocation: the scoring half's own noise and the estimate's lower it
(a perfect estimate of sigma would win more where sigma is heavy-tailed).

Printed per window (the estimate averaged over k x k pixels, as
adaptive sampling's window mean) and floor (the least share, as a fraction
of the mean, as min_samples): the gain, uniform relMSE over allocated
relMSE at equal total samples (above 1: the allocation wins).

    python3 scripts/allocation_bound.py PTSC SCENE [--size 256] [--spp 16]
        [--seeds 24] [--ref-spp 1024] [--work DIR]

Needs numpy. docs/performance.md, "Where the Cornell box's error is".
"""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from adaptive_savings import read_pfm  # noqa: E402 (the scripts' folder first)


def box_mean(a, k):
    """Mean over the k x k window about each pixel (edges repeated)."""
    r = k // 2
    padded = np.pad(a, r, mode="edge")
    out = np.zeros_like(a)
    for dy in range(k):
        for dx in range(k):
            out += padded[dy:dy + a.shape[0], dx:dx + a.shape[1]]
    return out / (k * k)


def allocation(estimate, floor):
    """Shares proportional to sqrt(estimate), at least `floor`, mean 1."""
    root = np.sqrt(estimate)
    lo, hi = 0.0, 1e9
    for _ in range(200):
        c = (lo + hi) / 2
        if np.maximum(floor, c * root).mean() > 1:
            hi = c
        else:
            lo = c
    return np.maximum(floor, lo * root)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("ptsc")
    ap.add_argument("scene")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--seeds", type=int, default=24)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--work")
    a = ap.parse_args()
    work = Path(a.work or tempfile.mkdtemp())
    work.mkdir(parents=True, exist_ok=True)
    def render(name, spp, seed, extra):
        out = work / f"{name}.pfm"
        subprocess.run([a.ptsc, "render", a.scene, "-o", str(out), "--resolution",
                        f"{a.size}x{a.size}", "--spp", str(spp), "--seed", str(seed),
                        "--noise", "off", "--force", "--restart"] + extra,
                       check=True, capture_output=True)
        return read_pfm(out).astype(np.float64)

    images = np.array([render(f"seed_{seed}", a.spp, 500 + seed, ["--sampler", "independent"])
                       for seed in range(a.seeds)])
    weight = render("reference", a.ref_spp, 99, []) ** 2 + 0.01
    half = a.seeds // 2
    # Per-sample variance over relMSE's weight, summed over the channels
    # (a pixel's channels share its samples).
    halves = [(images[h].var(0, ddof=1) * a.spp / weight).sum(-1)
              for h in (slice(0, half), slice(half, None))]
    print(f"{a.scene}: {a.size}², {a.seeds} seeds × {a.spp} spp; uniform relMSE at {a.spp} spp "
          f"≈ {(halves[0].mean() + halves[1].mean()) / 6 / a.spp:.4g}")
    print("| window | floor | gain (estimated on one half, scored on the other) |")
    print("|---|---|---|")
    for k in (1, 3, 5):
        for floor in (0.25, 0.4):
            gains = []
            for est, score in ((halves[0], halves[1]), (halves[1], halves[0])):
                n = allocation(box_mean(est, k), floor)
                gains.append(score.mean() / (score / n).mean())
            print(f"| {k}×{k} | {floor} | {np.mean(gains):.2f} ({gains[0]:.2f}, {gains[1]:.2f}) |")


if __name__ == "__main__":
    main()
