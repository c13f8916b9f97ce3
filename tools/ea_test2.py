#!/usr/bin/python3
"""Scores a run of cases/ea-test-2 (UK Environment Agency 2D benchmark Test 2).

Prints, at each of the benchmark's 16 output points (the depressions' centres), the water
level at 6, 12, 24 and 48 h beside the level its depression ends at when the inflow's water
fills the depressions in turn by volume alone (data/ea-test-2/fill.csv, made by
tools/make_ea_test2.py). With --plot, draws the levels' series.

    /usr/bin/python3 tools/ea_test2.py cases/ea-test-2/ea-test-2.nc --plot ea2.png
"""

import argparse
import csv
import os

import netCDF4
import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("nc")
    parser.add_argument("--fill", default=os.path.join(ROOT, "data", "ea-test-2", "fill.csv"))
    parser.add_argument("--plot")
    args = parser.parse_args()
    with open(args.fill) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    fill = {r["point"]: r for r in rows}
    nc = netCDF4.Dataset(args.nc)
    t = np.asarray(nc["series_time"][:], float)
    names = [str(n) for n in nc["gauge_name"][:]]
    depth = np.ma.filled(nc["gauge_depth"][:].astype(float), np.nan)
    if depth.shape[0] != len(t):
        depth = depth.T
    hours = [6, 12, 24, 48]
    print("point   x     y    floor (m)  level (m) at " + "  ".join(f"{h:>5}h" for h in hours)
          + "   by volume  difference")
    worst = 0.0
    levels = {}
    for g, name in enumerate(names):
        r = fill[name]
        floor = float(r["floor_m"])
        series = floor + np.nan_to_num(depth[:, g])
        levels[name] = series
        at = [series[int(np.argmin(np.abs(t - 3600.0 * h)))] for h in hours]
        expected = float(r["level_m"])
        diff = at[-1] - expected
        worst = max(worst, abs(diff))
        print(f"{name:>5} {float(r['x']):5.0f} {float(r['y']):5.0f}   {floor:8.4f}  "
              + "  ".join(f"{v:6.3f}" for v in at) + f"   {expected:8.4f}  {diff:+8.4f}")
    print(f"largest difference at 48 h: {worst:.4f} m")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(9, 5))
        colours = plt.get_cmap("tab20").colors
        for k, (name, series) in enumerate(levels.items()):
            if np.nanmax(series) - series[0] < 0.01:
                continue  # a depression the water never reached
            colour = colours[(2 * k) % 20 if k < 10 else (2 * k + 1) % 20]
            ax.plot(t / 3600.0, series, color=colour, label=f"point {name}")
            if float(fill[name]["depth_m"]) > 0.0:
                ax.axhline(float(fill[name]["level_m"]), color=colour, ls=":", lw=1)
        ax.set_xlabel("time (h)")
        ax.set_ylabel("water level at the depression's centre (m)")
        ax.set_title("EA Test 2: levels in the depressions the water reached\n"
                     "(dotted: the level of the depressions filled by volume alone)")
        ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)


if __name__ == "__main__":
    main()
