#!/usr/bin/python3
"""Score a run of NTHMP benchmark problem 6 (the conical island) against the laboratory.

    /usr/bin/python3 tools/nthmp_bp6.py CASE RESULT.nc [--plot FIGURE.png]

CASE is a, b or c. The run is cases/nthmp-bp6/case-CASE.json's: gauges g1 ... g22 and an
inundation line written as GeoJSON beside RESULT.nc (RESULT_inundation_line.geojson).

- The laboratory series (data/nthmp-bp6/ts2*.txt) have a zero offset of a millimetre or two
  before the wave; each gauge's mean over its first two seconds is taken off. The model's
  gauges on the island's slope read the still water within 2 mm of zero (the level of a cell
  two spacings wide on a 1:4 face); each model gauge's reading at t = 0 less the starting
  wave's rise there is taken off alike.
- The model's clock is shifted so that its crest passes gauge 2, the incident-wave gauge, when
  the laboratory's did (the problem leaves the wave's starting time to the modeller).
- Per gauge: the maximum wave height error (model - lab) / lab, and the normalised RMS of the
  series, RMS(model - lab) / max(lab), from three seconds before the crest at gauge 2 to the
  run's end.
- Run-up: along each radius of the laboratory's table (0 degrees towards -y, 90 towards +x,
  the island's lee), the ground elevation where the radius crosses the inundation line round
  the island, against the table's run-up (data/nthmp-bp6/run2*.txt, cm).
"""
import argparse
import json
import math
import pathlib
import sys

import numpy as np
from netCDF4 import Dataset

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE.parent / "data" / "nthmp-bp6"
CENTRE = (12.96, 13.80)
SERIES = {"a": "ts2a.txt", "b": "ts2b.txt", "c": "ts2cnew1.txt"}
RUNUP = {"a": "run2a.txt", "b": "run2b.txt", "c": "run2c.txt"}
GAUGES = ["g1", "g2", "g3", "g4", "g6", "g9", "g16", "g22"]


def numbers(line):
    try:
        return [float(f) for f in line.split()]
    except ValueError:
        return None


def lab_series(case):
    rows = [r for r in map(numbers, (DATA / SERIES[case]).read_text().splitlines())
            if r and len(r) == 9]
    table = np.array(rows)
    time = table[:, 0]
    levels = table[:, 1:]
    levels = levels - levels[time < time[0] + 2.0].mean(axis=0)
    return time, levels


def lab_runup(case):
    rows = [r for r in map(numbers, (DATA / RUNUP[case]).read_text().splitlines())
            if r and len(r) == 4]
    table = np.array(rows)
    return table[:, 1], table[:, 2] / 100.0  # degrees, m


def island_line(path):
    """The inundation line round the island: the line whose vertices lie closest to its axis."""
    features = json.loads(path.read_text())["features"]
    best, best_distance = None, math.inf
    for f in features:
        points = np.array(f["geometry"]["coordinates"])
        distance = np.hypot(points[:, 0] - CENTRE[0], points[:, 1] - CENTRE[1]).mean()
        if distance < best_distance:
            best, best_distance = points, distance
    return best


def runup_along(points, degrees):
    """The ground where the radius at `degrees` last crosses the line (Z interpolated)."""
    theta = math.radians(degrees)
    direction = np.array([math.sin(theta), -math.cos(theta)])
    normal = np.array([-direction[1], direction[0]])
    rel = points[:, :2] - np.array(CENTRE)
    side = rel @ normal
    along = rel @ direction
    best = (None, -math.inf)
    for k in range(len(points) - 1):
        if side[k] == side[k + 1] or side[k] * side[k + 1] > 0:
            continue
        w = side[k] / (side[k] - side[k + 1])
        reach = along[k] + w * (along[k + 1] - along[k])
        if reach > best[1]:
            best = (points[k, 2] + w * (points[k + 1, 2] - points[k, 2]), reach)
    return best[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", choices=["a", "b", "c"])
    parser.add_argument("result", type=pathlib.Path)
    parser.add_argument("--plot", type=pathlib.Path)
    args = parser.parse_args()

    with Dataset(args.result) as nc:
        names = [str(n) for n in nc["gauge_name"][:]]
        gauge_x = np.array(nc["gauge_x"][:])
        model_time = np.array(nc["series_time"][:])
        model = np.ma.filled(nc["gauge_surface_elevation"][:], np.nan)
        scene = json.loads(nc.getncattr("scenario"))
    lab_time, lab = lab_series(args.case)
    # The starting wave's rise at each gauge, and the model's still level there.
    wave = scene["water"][0]["solitary_wave"]
    height, depth, crest = wave["height"], wave["depth"], wave["crest"][0]
    gamma = math.sqrt(3.0 * height / (4.0 * depth))
    rise = height / np.cosh(gamma * (gauge_x - crest) / depth) ** 2
    model = model - (model[0] - rise)
    # Model columns in the order of the lab's.
    model = model[:, [names.index(g) for g in GAUGES]]

    g2 = GAUGES.index("g2")
    shift = lab_time[np.argmax(lab[:, g2])] - model_time[np.nanargmax(model[:, g2])]
    shifted = model_time + shift
    start = lab_time[np.argmax(lab[:, g2])] - 3.0
    window = (lab_time >= start) & (lab_time <= shifted[-1])
    print(f"case {args.case.upper()}: model clock + {shift:.3f} s; scored over "
          f"{start:.2f} to {shifted[-1]:.2f} s")
    print("gauge  lab max (m)  model max (m)  height error  normalised RMS")
    for k, g in enumerate(GAUGES):
        level = np.interp(lab_time[window], shifted, model[:, k])
        lab_max = lab[window, k].max()
        model_max = np.nanmax(level)
        nrms = math.sqrt(np.nanmean((level - lab[window, k]) ** 2)) / lab_max
        print(f"{g:5s}  {lab_max:11.4f}  {model_max:13.4f}  {100 * (model_max / lab_max - 1):+11.1f} %"
              f"  {100 * nrms:13.1f} %")

    line_file = args.result.with_name(args.result.stem + "_inundation_line.geojson")
    points = island_line(line_file)
    degrees, measured = lab_runup(args.case)
    computed = np.array([runup_along(points, d) for d in degrees], dtype=float)
    print("run-up: degrees, lab (m), model (m), error")
    for d, lab_r, mod_r in zip(degrees, measured, computed):
        print(f"  {d:6.1f}  {lab_r:.4f}  {mod_r:.4f}  {100 * (mod_r / lab_r - 1):+6.1f} %")
    print(f"maximum run-up: lab {measured.max():.4f} m at {degrees[np.argmax(measured)]:.1f} deg, "
          f"model {np.nanmax(computed):.4f} m at {degrees[np.nanargmax(computed)]:.1f} deg: "
          f"{100 * (np.nanmax(computed) / measured.max() - 1):+.1f} %")
    print(f"run-up around the island: mean |error| "
          f"{100 * np.nanmean(np.abs(computed / measured - 1)):.1f} %")

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(3, 3, figsize=(12, 9))
        for k, g in enumerate(GAUGES):
            ax = axes.flat[k]
            ax.plot(lab_time, lab[:, k] * 100, "k", lw=0.8, label="laboratory")
            ax.plot(shifted, model[:, k] * 100, "C3", lw=1, label="swe-mps")
            ax.set_xlim(start, shifted[-1])
            ax.set_title(g)
            ax.set_ylabel("surface (cm)")
        axes.flat[0].legend()
        ax = axes.flat[8]
        ax.plot(degrees, measured * 100, "ko", ms=4, label="laboratory")
        ax.plot(degrees, computed * 100, "C3.-", label="swe-mps")
        ax.set_xlabel("angle (degrees; 90 = lee)")
        ax.set_ylabel("run-up (cm)")
        ax.legend()
        fig.suptitle(f"NTHMP BP6, case {args.case.upper()}")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=90)
    return 0


if __name__ == "__main__":
    sys.exit(main())
