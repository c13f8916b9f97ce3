#!/usr/bin/python3
"""Plot swe-mps dam-break output against Ritter's analytic solution (method.md eq 14).

Reads one or more netCDF files written by `swe-mps run` and draws, at one output time, the
particle depths against x, the gridded depth averaged across the channel, and eq 14.

    /usr/bin/python3 tools/plot_ritter.py cases/ritter/ritter.nc -o ritter.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402

import ncrecords  # noqa: E402  (beside this script)


def ritter_depth(x, t, x_dam, h0, g):
    c0 = np.sqrt(g * h0)
    xi = (x - x_dam) / t
    h = (2.0 * c0 - xi) ** 2 / (9.0 * g)
    return np.where(xi <= -c0, h0, np.where(xi >= 2.0 * c0, 0.0, h))


def read_record(path, time):
    with netCDF4.Dataset(path) as ds:
        k, part = ncrecords.record(ds, time)
        return {
            "t": float(ds["time"][k]),
            "g": float(ds.getncattr("gravity_m_s2")),
            "px": ds["particle_x"][part],
            "ph": ds["particle_depth"][part],
            "x": ds["x"][:],
            "grid": ds["depth"][k, :, :].mean(axis=0),
        }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="netCDF files from swe-mps run")
    ap.add_argument("--labels", nargs="*", help="one label per file")
    ap.add_argument("--time", type=float, help="output time in s (default: the last)")
    ap.add_argument("--x-dam", type=float, default=4.65, help="dam position in m")
    ap.add_argument("--h0", type=float, default=0.25, help="initial depth in m")
    ap.add_argument("--xlim", type=float, nargs=2, default=(2.5, 6.8))
    ap.add_argument("-o", "--output", default="ritter.png")
    args = ap.parse_args()
    labels = args.labels or args.files

    fig, ax = plt.subplots(figsize=(9, 4.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    t = g = None
    for k, (path, label) in enumerate(zip(args.files, labels)):
        rec = read_record(path, args.time)
        t, g = rec["t"], rec["g"]
        c = colors[k % len(colors)]
        ax.plot(rec["px"], rec["ph"], ".", ms=2.5, color=c, alpha=0.6, label=f"{label}: particle depth")
        ax.plot(rec["x"], rec["grid"], "-", lw=1.2, color=c, label=f"{label}: gridded depth, mean across y")
    x = np.linspace(args.xlim[0], args.xlim[1], 2000)
    ax.plot(x, ritter_depth(x, t, args.x_dam, args.h0, g), "k-", lw=2, label="Ritter (eq 14)")
    ax.set_xlim(*args.xlim)
    ax.set_ylim(0.0, 1.15 * args.h0)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("depth (m)")
    ax.set_title(f"Dam break, t = {t:.2f} s")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
