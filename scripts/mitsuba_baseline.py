#!/usr/bin/env python3
"""Mitsuba 3's own noise at the spp of the reference test, for tests/mitsuba/.

  python3 scripts/mitsuba_baseline.py [--res 64] [--spp 64] [--seeds 8] [--out tests/mitsuba]

For each of cornell, mesh and spheres (../shared/bench/SCENES.md) renders
Mitsuba's `path` integrator at RES x RES and SPP with several seeds, compares
every image with the committed high-spp reference (REFDIR/<scene>_ref_*.exr,
made by `bash ../shared/bench/mitsuba.sh ref SCENE 64 65536`), and writes
`baseline.json`: the per-seed and median `mae_over_mean` (compare.py's metric).
The Rust test `mitsuba_reference` renders ptsc at the same size and spp and
must not be noisier than that median.
"""
import argparse
import glob
import json
import statistics
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT.parent / "shared" / "bench"
sys.dont_write_bytecode = True
sys.path.insert(0, str(BENCH))
import mitsuba as mi  # noqa: E402
import mitsuba_scenes as MS  # noqa: E402
import scenes as S  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--out", type=Path, default=ROOT / "tests" / "mitsuba")
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    # Other scenes' entries (textures: scripts/mitsuba_textures.py) are kept.
    old = a.out / "baseline.json"
    kept = json.loads(old.read_text())["scenes"] if old.exists() else {}
    out = {"mitsuba": mi.__version__, "variant": "scalar_rgb", "res": a.res, "spp": a.spp, "scenes": kept}
    for name in ("cornell", "mesh", "spheres"):
        ref_path = sorted(glob.glob(str(a.out / f"{name}_ref_{a.res}_*spp.exr")))[-1]
        ref = np.array(mi.Bitmap(ref_path), dtype=np.float64)[..., :3]
        scene = mi.load_dict(MS.to_mitsuba(S.SCENES[name], res=(a.res, a.res), spp=a.spp))
        maes = []
        for seed in range(a.seeds):
            img = np.array(mi.render(scene, spp=a.spp, seed=seed), dtype=np.float64)[..., :3]
            maes.append(float(np.abs(img - ref).mean() / ref.mean()))
        out["scenes"][name] = {"reference": Path(ref_path).name, "mae_over_mean": maes,
                               "median_mae_over_mean": statistics.median(maes)}
        print(name, f"median MAE/mean {statistics.median(maes):.5f}", [round(m, 5) for m in maes], flush=True)
    (a.out / "baseline.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
