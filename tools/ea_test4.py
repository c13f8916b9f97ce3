#!/usr/bin/python3
"""Scores a run of cases/ea-test-4 (UK Environment Agency 2D benchmark Test 4).

Prints, at each of the benchmark's six output points, the depth at 1 h to 5 h and the
peak depth with its time, and the depth along y = 1000 m at 1 h beside the bands read off
the benchmark report's Figure 4.13 (docs/benchmarks.md says where they come from and how far
they can be trusted). With --plot, draws the gauges' depth series and the 1 h section.

    /usr/bin/python3 tools/ea_test4.py cases/ea-test-4/ea-test-4.nc --plot ea4.png
"""

import argparse
import sys

import netCDF4
import numpy as np

# Depth (m) along y = 1000 m at t = 1 h: x (m) -> (low, high), read by eye off Figure 4.13
# of Neelz & Pender 2013 (SC120002) by a third party, good to about +/- 0.02 m
# (stathis-liap/Beirut_Project @ 37fbef3e, scripts/benchmark_ea4.py, PUBLISHED_XS_1H).
SECTION_1H = {
    25: (0.32, 0.46), 50: (0.29, 0.36), 100: (0.25, 0.29), 150: (0.21, 0.25),
    200: (0.18, 0.21), 250: (0.15, 0.18), 300: (0.11, 0.14), 350: (0.06, 0.10),
    400: (0.00, 0.04),
}


def read(path):
    f = netCDF4.Dataset(path)
    out = {
        "t": np.asarray(f["series_time"][:], float),
        "names": [str(n) for n in f["gauge_name"][:]],
        "gauge": np.ma.filled(f["gauge_depth"][:].astype(float), np.nan),
        "x": np.asarray(f["x"][:], float),
        "y": np.asarray(f["y"][:], float),
        "map_t": np.asarray(f["time"][:], float),
        "depth": f["depth"],
    }
    return f, out


def section(run, t_s, y_m=1000.0):
    k = int(np.argmin(np.abs(run["map_t"] - t_s)))
    if abs(run["map_t"][k] - t_s) > 1.0:
        sys.exit(f"no map at t = {t_s} s")
    y = run["y"]
    # The two rows either side of y = 1000 m (cell edges lie on it at 5 m and 10 m cells).
    rows = np.argsort(np.abs(y - y_m))[:2]
    d = np.ma.filled(run["depth"][k, :, :].astype(float), 0.0)
    return run["x"], d[rows, :].mean(axis=0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("nc")
    parser.add_argument("--plot")
    args = parser.parse_args()
    f, run = read(args.nc)
    t = run["t"]
    print("gauge      x, y (m)     depth (m) at 1h    2h     3h     4h     5h   peak (m) at (h)")
    for g, name in enumerate(run["names"]):
        series = np.nan_to_num(run["gauge"][:, g], nan=0.0)
        at = [np.interp(h * 3600.0, t, series) for h in (1, 2, 3, 4, 5)]
        peak = int(np.argmax(series))
        gx, gy = float(f["gauge_x"][g]), float(f["gauge_y"][g])
        print(f"{name:>5}  ({gx:4.0f}, {gy:4.0f})   " + "  ".join(f"{v:5.3f}" for v in at) +
              f"   {series[peak]:5.3f} at {t[peak] / 3600:4.2f}")
    x, d = section(run, 3600.0)
    print("\ndepth along y = 1000 m at 1 h against the bands read off the report's Figure 4.13")
    inside = 0
    for xs, (lo, hi) in SECTION_1H.items():
        v = float(np.interp(xs, x, d))
        ok = lo - 1e-9 <= v <= hi + 1e-9
        inside += ok
        print(f"  x = {xs:3d} m: {v:5.3f} m, band {lo:.2f}-{hi:.2f}  {'inside' if ok else 'OUTSIDE'}")
    print(f"{inside} of {len(SECTION_1H)} inside")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
        for g, name in enumerate(run["names"]):
            a.plot(t / 3600.0, np.nan_to_num(run["gauge"][:, g]), label=f"point {name}")
        a.set_xlabel("time (h)")
        a.set_ylabel("depth (m)")
        a.legend()
        a.set_title("EA Test 4: depth at the output points")
        b.plot(x, d, "k-", label="swe-mps, 1 h")
        for xs, (lo, hi) in SECTION_1H.items():
            b.plot([xs, xs], [lo, hi], "r-", lw=4, alpha=0.5)
        b.plot([], [], "r-", lw=4, alpha=0.5, label="report's Fig. 4.13, read by eye")
        b.set_xlim(0, 600)
        b.set_xlabel("x along y = 1000 m (m)")
        b.set_ylabel("depth (m)")
        b.legend()
        b.set_title("depth along the centre line at 1 h")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)


if __name__ == "__main__":
    main()
