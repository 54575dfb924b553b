#!/usr/bin/env python3
"""Equal-time error against Mitsuba 3 (issue 40's table).

For each bench scene: a high-spp Mitsuba reference (../shared/bench/mitsuba.sh
ref), Mitsuba llvm_ad_rgb at 64 spp (median time of 3 runs, 2 threads; the
image of run 0), then ptsc for that same time (--time, 2 threads) with the
Sobol sampler uniformly, adaptively (--noise), and uniformly with --denoise
(a build with the feature; the denoising's own time is reported beside it).
relMSE: mean over pixels and channels of (x - r)^2 / (r^2 + 0.01).

    python3 scripts/equal_time.py PTSC PTSC_DENOISE [--res 256] [--ref-spp 4096]
        [--scenes cornell,mesh,spheres] [--noise 0.01] [--seeds 3]
        [--integrators ptlt,ptlt:0.05,ptlt:0.05:4,bdpt]

PTSC_DENOISE runs with LD_LIBRARY_PATH set to target/oidn/lib; "-" leaves the
denoised column out. Needs numpy and
mitsuba (for EXR reading and the Mitsuba runs).
"""
import argparse
import os
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT.parent / "shared" / "bench"


def read_exr(path):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    bitmap = mi.Bitmap(str(path))
    layers = dict(bitmap.split())
    return np.array(layers.get("<root>", bitmap), dtype=np.float64)[..., :3]


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2)))


def mitsuba(args, out, env_extra):
    env = dict(os.environ, OUT=str(out), **env_extra)
    return subprocess.run(["bash", str(BENCH / "mitsuba.sh")] + args, env=env,
                          capture_output=True, text=True, check=True).stdout


def ptsc(binary, scene, out, res, seconds, seed, extra, env=None):
    line = subprocess.run(
        [binary, "render", str(ROOT / "examples/bench" / f"{scene}.pts"), "-o", str(out),
         "--resolution", f"{res}x{res}", "--time", f"{seconds}s", "--threads", "2",
         "--seed", str(seed), "--force", "--restart"]
        + (extra if "--noise" in extra else extra + ["--noise", "off"]),
        capture_output=True, text=True, check=True, env=env).stderr
    line = next(l for l in line.splitlines() if "paths/s" in l)
    spp = re.search(r"[\d.]+ on average", line) or re.search(r"\d+ spp", line)
    secs = float(re.search(r" in ([\d.]+) s ", line).group(1))
    return spp.group(0), secs


def integrator_run(entry, binary):
    """A run of another integrator: "ptlt" uniformly, "ptlt:0.05" with --noise
    0.05, "ptlt:0.05:4" also with --min-samples 4."""
    name, noise, least = (entry.split(":") + ["", ""])[:3]
    extra = ["--integrator", name] + (["--noise", noise] if noise else [])
    extra += ["--min-samples", least] if least else []
    label = f"sobol, {name}" + (f" + --noise {noise}" if noise else "")
    label += f" --min-samples {least}" if least else ""
    return (label, binary, extra, None)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("ptsc")
    p.add_argument("ptsc_denoise")
    p.add_argument("--res", type=int, default=256)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--scenes", default="cornell,mesh,spheres")
    p.add_argument("--noise", default="0.01")
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--work", help="folder for the files (references kept there are reused)")
    p.add_argument("--integrators", default="",
                   help="comma-separated integrators also run, each uniformly (ptlt) "
                        "or adaptively with a noise threshold (ptlt:0.05)")
    a = p.parse_args()
    tmp = Path(a.work) if a.work else Path(tempfile.mkdtemp())
    tmp.mkdir(parents=True, exist_ok=True)
    oidn = dict(os.environ, LD_LIBRARY_PATH=str(ROOT / "target/oidn/lib"))
    rows = []
    for scene in a.scenes.split(","):
        ref_path = tmp / f"{scene}_ref_{a.res}_{a.ref_spp}spp.exr"
        if not ref_path.exists():
            mitsuba(["ref", scene, str(a.res), str(a.ref_spp)], tmp, {})
        ref = read_exr(ref_path)
        line = mitsuba(["bench", scene], tmp, {"RES": str(a.res), "SPP": "64", "RUNS": "3",
                                                "THREADS": "2", "VARIANTS": "llvm_ad_rgb"})
        seconds = float(next(l for l in line.splitlines() if l.startswith(scene)).split()[2])
        m_err = rel_mse(read_exr(tmp / f"{scene}_mitsuba_llvm_ad_rgb_{a.res}_64spp.exr"), ref)
        results = {}
        runs = [
            ("sobol", a.ptsc, [], None),
            (f"sobol + --noise {a.noise}", a.ptsc, ["--noise", a.noise], None),
            ("sobol + --denoise", a.ptsc_denoise, ["--denoise"], oidn),
        ] + [integrator_run(i, a.ptsc) for i in a.integrators.split(",") if i]
        for name, binary, extra, env in [r for r in runs if r[1] != "-"]:
            errs, spps = [], []
            for seed in range(a.seeds):
                out = tmp / f"{scene}_{seed}.exr"
                spp, _ = ptsc(binary, scene, out, a.res, seconds, 1000 + seed, extra, env)
                spps.append(spp)
                errs.append(rel_mse(read_exr(out), ref))
            results[name] = (float(np.mean(errs)), spps)
        rows.append((scene, seconds, m_err, results))
        print(f"{scene}: Mitsuba llvm 64 spp {seconds:.2f} s relMSE {m_err:.4g}; " +
              "; ".join(f"{k} {v[0]:.4g} ({', '.join(v[1])})" for k, v in results.items()), flush=True)
    print(f"\n{a.res}², reference Mitsuba {a.ref_spp} spp; ptsc {a.seeds} seeds, 2 threads, --time = Mitsuba's 64-spp time")
    names = list(rows[0][3].keys())
    print("| scene | Mitsuba llvm 64 spp: time, relMSE | " + " | ".join(f"ptsc {n}: relMSE (× Mitsuba's)" for n in names) + " |")
    print("|---" * (2 + len(names)) + "|")
    for scene, seconds, m_err, results in rows:
        cells = " | ".join(f"{results[n][0]:.4g} ({results[n][0] / m_err:.2f}×)" for n in names)
        print(f"| {scene} | {seconds:.2f} s, {m_err:.4g} | {cells} |")


if __name__ == "__main__":
    main()
