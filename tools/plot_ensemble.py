#!/usr/bin/python3
"""Exceedance-probability maps of a swe-mps ensemble (ensemble.nc), one panel per depth
threshold, over a hillshade of the terrain.

The terrain is the bed_elevation of a member's result (by default the first member's
result.nc beside ensemble.nc). Cells no member flooded past a threshold show as relief; the
panels show the part of the grid any member flooded (--whole-grid: all of it).

    /usr/bin/python3 tools/plot_ensemble.py cases/valley-flood/ensemble/ensemble.nc \
        --out probability.png
"""
import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_flood_map import crs_name, grid_extent, hillshade  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("products", help="the ensemble's ensemble.nc")
    parser.add_argument("--terrain", help="a member's result.nc with bed_elevation "
                        "(default: the first member's)")
    parser.add_argument("--out", default="ensemble_probability.png")
    parser.add_argument("--whole-grid", action="store_true",
                        help="show the whole grid, not only the part any member flooded")
    args = parser.parse_args()

    ds = netCDF4.Dataset(args.products)
    x, y = ds["x"][:], ds["y"][:]
    extent, dx, dy = grid_extent(x, y)
    thresholds = ds["depth_threshold"][:]
    probability = ds["exceedance_probability"][:]
    combined = ds.getncattr("ensemble_members_combined")
    total = ds.getncattr("ensemble_members")

    terrain = args.terrain
    if terrain is None:
        members = sorted(glob.glob(os.path.join(os.path.dirname(args.products) or ".",
                                                "member-*", "result.nc")))
        terrain = members[0] if members else None
    shade = None
    if terrain:
        with netCDF4.Dataset(terrain) as t:
            if "bed_elevation" in t.variables:
                shade = hillshade(t["bed_elevation"][:], dx, dy)

    km = 1000.0 if extent[1] - extent[0] > 1000.0 else 1.0
    shown = [e / km for e in extent]
    # The part any member flooded, with a margin, unless the whole grid is asked for.
    flooded = np.ma.filled(np.ma.masked_invalid(probability[0].astype(float)), 0.0) > 0.0
    zoom = None
    if not args.whole_grid and flooded.any():
        rows, cols = np.nonzero(flooded)
        margin = max(3, int(0.15 * max(np.ptp(rows), np.ptp(cols))))
        r0, r1 = max(rows.min() - margin, 0), min(rows.max() + margin, flooded.shape[0] - 1)
        c0, c1 = max(cols.min() - margin, 0), min(cols.max() + margin, flooded.shape[1] - 1)
        zoom = ((x[c0] - dx / 2) / km, (x[c1] + dx / 2) / km,
                (y[r0] - dy / 2) / km, (y[r1] + dy / 2) / km)
    n = len(thresholds)
    cols = 2 if n > 1 else 1
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.6 * rows), squeeze=False,
                             constrained_layout=True)
    image = None
    for j, ax in enumerate(axes.flat):
        if j >= n:
            ax.axis("off")
            continue
        if shade is not None:
            ax.imshow(shade, origin="lower", extent=shown, cmap="gray", vmin=0, vmax=1)
        p = np.ma.masked_invalid(np.ma.filled(probability[j].astype(float), np.nan))
        p = np.ma.masked_where(p <= 0.0, p)
        image = ax.imshow(p, origin="lower", extent=shown, cmap="YlGnBu", vmin=0.0, vmax=1.0,
                          alpha=0.9, interpolation="nearest")
        ax.set_title(f"depth > {thresholds[j]:g} m")
        if zoom:
            ax.set_xlim(zoom[0], zoom[1])
            ax.set_ylim(zoom[2], zoom[3])
        unit = "km" if km > 1.0 else "m"
        ax.set_xlabel(f"x ({unit})")
        ax.set_ylabel(f"y ({unit})")
    fig.colorbar(image, ax=axes, shrink=0.8,
                 label=f"fraction of the {combined} members whose maximum depth exceeds it")
    crs = crs_name(ds)
    fig.suptitle(f"{ds.title}, {combined} of {total} members" + (f" ({crs})" if crs else ""))
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
