#!/usr/bin/env python3
"""Writes src/light/sun_table.rs: the sun's radiance (linear sRGB) for
elevations 0..=90 degrees (1-degree steps) and turbidities 1..=10, from
Mitsuba 3.9.1's `sunsky` emitter (scalar_rgb; its Hosek-Wilkie 2013 solar
radiance model, reduced to RGB, disk of uniform radiance). ptsc
interpolates linearly in both, which reproduces Mitsuba's values (Mitsuba
interpolates linearly between coarser knots). Negative values (Mitsuba
gives blue -58 below 2 degrees) are clamped to 0.

  python3 scripts/sun_table.py
"""
import math
from pathlib import Path

import mitsuba as mi

ROOT = Path(__file__).resolve().parent.parent


def sun(elevation_deg, turbidity):
    el = math.radians(elevation_deg)
    # Mitsuba's sky is z-up; the sun at azimuth -y.
    d = [0.0, -math.cos(el), math.sin(el)]
    e = mi.load_dict({"type": "sunsky", "sun_direction": d, "turbidity": turbidity,
                      "albedo": 0.3, "sky_scale": 0.0})
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(-d[0], -d[1], -d[2])
    return [max(0.0, float(x)) for x in e.eval(si)]


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    rows = []
    for t in range(1, 11):
        for el in range(0, 91):
            # At 0 degrees Mitsuba's sun has set; take it at the horizon.
            r = sun(max(el, 1e-3), t)
            rows.append("    [" + ", ".join(f"{x:.6}" for x in r) + f"], // T {t}, {el} deg")
    text = (
        "//! The sun's radiance per elevation and turbidity, written by\n"
        "//! `scripts/sun_table.py` (see there); do not edit by hand.\n\n"
        "/// [turbidity 1..=10][elevation 0..=90 degrees] → linear-sRGB radiance.\n"
        f"pub const SUN_RADIANCE: [[f32; 3]; {len(rows)}] = [\n" + "\n".join(rows) + "\n];\n"
    )
    (ROOT / "src" / "light" / "sun_table.rs").write_text(text)


if __name__ == "__main__":
    main()
