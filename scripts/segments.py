#!/usr/bin/env python3
"""Time by path segment: ptsc and Mitsuba 3 `llvm_ad_rgb` at several max_depth.

  python3 scripts/segments.py [--ptsc target/release/ptsc] [--spp 16] [--res 512]
                              [--depths 1,2,3,8] [--runs 3] [SCENE...]

For each bench scene (default cornell mesh spheres) renders ptsc's
examples/bench/SCENE.pts with its `max_depth` replaced (a copy in a
temporary folder, the files it names made absolute) and Mitsuba's version
of the scene (../shared/bench/mitsuba_scenes.py) at each depth, 2 threads.
ptsc: the median of RUNS render times ("in T s"); Mitsuba: the median of
RUNS renders after one warm-up render in the same process (its kernels are
compiled on the first). The difference between consecutive depths is the
time of those segments (docs/performance.md, "Where the time goes, segment by
segment"). Needs mitsuba==3.9.1 and libLLVM (DRJIT_LIBLLVM_PATH, as
../shared/bench/mitsuba.sh sets it).
"""
import argparse
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT.parent / "shared" / "bench"
sys.dont_write_bytecode = True
sys.path.insert(0, str(BENCH))


def ptsc_time(binary, scene, depth, spp, res, runs):
    """Median render time of ptsc on `scene` with `max_depth` `depth`."""
    src = ROOT / "examples" / "bench" / f"{scene}.pts"
    text = re.sub(r"max_depth\s+\d+", f"max_depth {depth}", src.read_text())
    # A string naming a file beside the scene (the mesh's PLY) is made
    # absolute, so that the copy reads the same file from elsewhere.
    text = re.sub(r'"([^"]+)"', lambda m: f'"{(src.parent / m.group(1)).resolve()}"'
                  if (src.parent / m.group(1)).is_file() else m.group(0), text)
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / f"{scene}.pts"
        copy.write_text(text)
        for _ in range(runs):
            line = subprocess.run(
                [binary, "render", str(copy), "--spp", str(spp), "--resolution", f"{res}x{res}",
                 "--threads", "2", "-o", f"{tmp}/s.exr"],
                check=True, capture_output=True, text=True).stderr.strip().splitlines()[-1]
            times.append(float(re.search(r" in ([0-9.]+) s ", line).group(1)))
    return statistics.median(times)


def mitsuba_time(scene, depth, spp, res, runs):
    """Median render time of Mitsuba llvm_ad_rgb after a warm-up render."""
    import drjit as dr
    import mitsuba as mi
    import mitsuba_scenes as MS
    import scenes as S
    mi.set_variant("llvm_ad_rgb")
    dr.set_thread_count(2)
    loaded = mi.load_dict(MS.to_mitsuba(S.SCENES[scene], res=(res, res), spp=spp, max_depth=depth))
    times = [MS.render_timed(loaded, spp, seed=r)[1] for r in range(runs + 1)]
    return statistics.median(times[1:])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="*", default=["cornell", "mesh", "spheres"])
    ap.add_argument("--ptsc", default=str(ROOT / "target" / "release" / "ptsc"))
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--res", type=int, default=512)
    ap.add_argument("--depths", default="1,2,3,8")
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    depths = [int(d) for d in a.depths.split(",")]
    print("| scene | renderer | " + " | ".join(f"depth {d}" for d in depths) + " |")
    print("| --- | --- | " + " | ".join("---:" for _ in depths) + " |")
    for scene in a.scenes:
        p = [ptsc_time(a.ptsc, scene, d, a.spp, a.res, a.runs) for d in depths]
        m = [mitsuba_time(scene, d, a.spp, a.res, a.runs) for d in depths]
        print(f"| {scene} | ptsc | " + " | ".join(f"{t:.3f}" for t in p) + " |", flush=True)
        print(f"| {scene} | llvm_ad_rgb | " + " | ".join(f"{t:.3f}" for t in m) + " |", flush=True)


if __name__ == "__main__":
    main()
