#!/usr/bin/python3
"""Measure how much of a long wave an open sea boundary sends back, at normal and oblique incidence.

A solitary wave (H/d = 0.01, d = 1 m) runs across a basin 100 m long and 60 m wide, walled on
three sides, and meets an open sea boundary along its east edge, head on or at 30 or 60
degrees to the boundary's normal. What comes back is the difference, at a gauge 10 m inside the
boundary on the basin's axis, between the run and the same wave in a basin twice as long
(x up to 200 m), where nothing returns in the time measured: the walls are the same, so the
difference is the east end's alone. It is reported as a fraction of the incident wave's height
at the gauge. The window closes 12 s after the crest has passed the gauge, before the still
water behind the wave grows its particle-scale ripples (docs/tsunami.md, "Limits"). A walled
east end (a full reflection) is measured the same way as a check of the measure.

    /usr/bin/python3 tools/sea_boundary_reflection.py [--cli build/swe-mps] [--spacing 0.4]
        [--keep DIR]

Prints one line per case ("normal: 0.9 % of the incident height ...") and writes the scenes
and their gauge series to DIR (a temporary folder unless given).
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
DEPTH, HEIGHT, WIDTH, LENGTH = 1.0, 0.01, 60.0, 100.0
CREST = (40.0, 30.0)
GAUGE = (LENGTH - 10.0, 30.0)


def scene(name, length, angle_deg, end, spacing, open_end):
    """The basin from x = 0 to `length`, the wave moving at angle_deg north of east."""
    a = math.radians(angle_deg)
    corners = [[length, 0.0], [0.0, 0.0], [0.0, WIDTH], [length, WIDTH]]
    walls = [{"polyline": corners + ([[length, 0.0]] if not open_end else [])}]
    s = {
        "name": name,
        "end_time": end,
        "domain": {"x_min": 0, "x_max": length, "y_min": 0, "y_max": WIDTH},
        "water": [{
            "rectangle": {"x_min": 0, "x_max": length, "y_min": 0, "y_max": WIDTH},
            "depth": DEPTH,
            "spacing": spacing,
            "solitary_wave": {"height": HEIGHT, "crest": list(CREST),
                              "direction": [math.cos(a), math.sin(a)]},
        }],
        "walls": walls,
        "output": {
            "path": name + ".nc",
            "grid": {"spacing": spacing},
            "series_interval": 0.05,
            "gauges": [{"name": "g", "x": GAUGE[0], "y": GAUGE[1]}],
            "particles": False,
        },
    }
    if open_end:
        s["sea_boundaries"] = [{"line": [[length, 0.0], [length, WIDTH]], "type": "open"}]
    return s


def run(cli, folder, s):
    path = folder / (s["name"] + ".json")
    path.write_text(json.dumps(s, indent=1))
    subprocess.run([cli, "run", str(path), "-q"], check=True)
    rows = list(csv.DictReader(open(folder / (s["name"] + "_gauges.csv"))))
    return [(float(r["time_s"]), float(r["g_surface_elevation_m"]) - DEPTH) for r in rows]


def value_at(series, t):
    for (t0, v0), (t1, v1) in zip(series, series[1:]):
        if t0 <= t <= t1:
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    return series[-1][1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", default=str(HERE.parent / "build" / "swe-mps"))
    parser.add_argument("--spacing", type=float, default=0.4)
    parser.add_argument("--keep", type=pathlib.Path)
    args = parser.parse_args()
    folder = args.keep or pathlib.Path(tempfile.mkdtemp(prefix="sea-reflection-"))
    folder.mkdir(parents=True, exist_ok=True)
    speed = math.sqrt(9.81 * (DEPTH + HEIGHT))
    cases = [("normal", 0.0, True), ("30 degrees", 30.0, True), ("60 degrees", 60.0, True),
             ("walled end", 0.0, False)]
    for label, angle, open_end in cases:
        a = math.radians(angle)
        # The crest passes the gauge when it has moved (gauge - crest) . direction.
        passing = ((GAUGE[0] - CREST[0]) * math.cos(a) + (GAUGE[1] - CREST[1]) * math.sin(a)) / speed
        end = passing + 12.0
        tag = label.split()[0]
        reference = run(args.cli, folder,
                        scene("reference-" + tag, 2 * LENGTH, angle, end, args.spacing, False))
        result = run(args.cli, folder,
                     scene("case-" + tag, LENGTH, angle, end, args.spacing, open_end))
        incident = max(v for _, v in reference)
        back = max(abs(v - value_at(reference, t)) for t, v in result)
        print(f"{label}: {100 * back / incident:.1f} % of the incident height "
              f"({back * 1000:.3f} mm of {incident * 1000:.2f} mm) at ({GAUGE[0]:g}, {GAUGE[1]:g}) m "
              f"over {end:.1f} s", flush=True)
    print(f"scenes and series in {folder}")


if __name__ == "__main__":
    sys.exit(main())
