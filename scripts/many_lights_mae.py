#!/usr/bin/env python3
"""Equal-time noise of the light selection rules on examples/many_lights.pts
(10,000 sphere lamps): MAE/mean against a high-spp reference of the default
rule, with each rule's sample count chosen so that its render takes as long
as the default's at --spp.

  python3 scripts/many_lights_mae.py [--bin target/release/ptsc] [--res 160x90]
      [--spp 64] [--ref-spp 4096] [--seeds 3] [--rules power,uniform]

Prints, per rule: seconds per sample, the equal-time spp, MAE/mean at equal
spp and at equal time. Needs numpy and mitsuba (to read EXR).
"""
import argparse
import re
import subprocess
import tempfile
from pathlib import Path

import mitsuba as mi
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "examples" / "many_lights.pts"


def render(args, out, spp, rule, seed):
    cmd = [args.bin, "render", str(SCENE), "--spp", str(spp), "--resolution", args.res,
           "--seed", str(seed), "--light-selection", rule, "--threads", "2", "-o", str(out)]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stderr
    seconds = float(re.search(r" in ([0-9.]+) s ", text).group(1))
    img = np.array(mi.Bitmap(str(out)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                               srgb_gamma=False), dtype=np.float64)
    return img, seconds


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "ptsc"))
    ap.add_argument("--res", default="160x90")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--rules", default="power,uniform")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    tmp = Path(tempfile.mkdtemp())
    ref, t = render(args, tmp / "ref.exr", args.ref_spp, "auto", 999)
    print(f"reference: auto, {args.ref_spp} spp, {t:.1f} s")

    def mae(img):
        return float(np.abs(img - ref).mean() / ref.mean())

    def run(rule, spp):
        results = [render(args, tmp / f"{rule}.exr", spp, rule, seed) for seed in range(args.seeds)]
        return (float(np.median([mae(i) for i, _ in results])),
                float(np.median([s for _, s in results])))

    auto_mae, auto_time = run("auto", args.spp)
    print(f"auto: {args.spp} spp in {auto_time:.2f} s, MAE/mean {auto_mae:.4f}")
    for rule in args.rules.split(","):
        same_spp_mae, t = run(rule, args.spp)
        spp = max(1, round(args.spp * auto_time / t))
        equal_time_mae, t2 = run(rule, spp)
        print(f"{rule}: {args.spp} spp in {t:.2f} s (MAE/mean {same_spp_mae:.4f}, "
              f"{same_spp_mae / auto_mae:.2f}x auto's); equal time: {spp} spp in {t2:.2f} s, "
              f"MAE/mean {equal_time_mae:.4f} = {equal_time_mae / auto_mae:.2f}x auto's")


if __name__ == "__main__":
    main()
