#!/usr/bin/python3
"""Plan views of swe-mps particles, one panel per netCDF file, coloured by depth.

Each particle is drawn as a dot whose area is proportional to its volume, so split
particles show as smaller dots (the seed paper's figure 8). With --bed, a side view is
added under each plan view: the water surface z_b + h of every particle over the bed,
for a bed given as a piecewise-linear profile in x.

    /usr/bin/python3 tools/plot_particles.py a.nc b.nc --labels "no split" "split" -o p.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402

import ncrecords  # noqa: E402  (beside this script)


def read_particles(path, time):
    with netCDF4.Dataset(path) as ds:
        k, part = ncrecords.record(ds, time)
        first = ncrecords.record(ds, 0.0)[1]
        return {
            "t": float(ds["time"][k]),
            "x": ds["particle_x"][part],
            "y": ds["particle_y"][part],
            "h": ds["particle_depth"][part],
            "V": ds["particle_volume"][part],
            "V0": float(ds["particle_volume"][first].max()),  # largest at t = 0
        }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="netCDF files from swe-mps run, written with particles")
    ap.add_argument("--labels", nargs="*", help="one label per file")
    ap.add_argument("--time", type=float, help="output time in s (default: the last)")
    ap.add_argument("--xlim", type=float, nargs=2)
    ap.add_argument("--bed", type=float, nargs="+", metavar="X_Z",
                    help="bed profile as x1 z1 x2 z2 ... (adds a side view)")
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", default="particles.png")
    args = ap.parse_args()
    labels = args.labels or args.files
    rows = len(args.files) * (2 if args.bed else 1)
    fig, axes = plt.subplots(rows, 1, figsize=(11, 2.4 * rows), squeeze=False)
    axes = axes[:, 0]
    records = [read_particles(f, args.time) for f in args.files]
    hmax = max(float(r["h"].max()) for r in records)
    for k, (rec, label) in enumerate(zip(records, labels)):
        ax = axes[k * (2 if args.bed else 1)]
        size = 14.0 * rec["V"] / rec["V0"]
        sc = ax.scatter(rec["x"], rec["y"], s=size, c=rec["h"], cmap="viridis", vmin=0, vmax=hmax,
                        linewidths=0)
        ax.set_ylabel("y (m)")
        ax.set_title(f"{label}: {len(rec['x'])} particles, t = {rec['t']:.2f} s", fontsize=10)
        if args.xlim:
            ax.set_xlim(*args.xlim)
        fig.colorbar(sc, ax=ax, label="depth (m)", fraction=0.03, pad=0.01)
        if args.bed:
            side = axes[k * 2 + 1]
            bx = np.array(args.bed[0::2])
            bz = np.array(args.bed[1::2])
            zb = np.interp(rec["x"], bx, bz)
            lo, hi = args.xlim if args.xlim else (float(rec["x"].min()), float(rec["x"].max()))
            xs = np.linspace(lo, hi, 400)
            side.fill_between(xs, np.interp(xs, bx, bz) - 0.05, np.interp(xs, bx, bz), color="0.75",
                              label="bed")
            side.scatter(rec["x"], zb + rec["h"], s=2, c="tab:blue", label="water surface z_b + h")
            side.set_ylabel("z (m)")
            side.set_xlim(lo, hi)
            side.legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel("x (m)")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)


if __name__ == "__main__":
    main()
