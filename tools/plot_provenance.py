#!/usr/bin/python3
"""Where the water came from, from a swe-mps netCDF file written with output.provenance.

Map mode draws one source's share of each cell's water (max_source_share over the run, or
source_share at --time) over a hillshade of the file's bed_elevation; cells that were never wet
show the relief. Gauge mode (--gauges) draws, for each gauge, the depth at the gauge split into
the sources' shares of it over time (stacked), and the mean-age map is drawn with --age.

    /usr/bin/python3 tools/plot_provenance.py run.nc --source "upper lake" --out share.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --source river --time 7200 --out s.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --gauges gauges.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --age --out age.png
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402


def hillshade(bed, dx):
    """Lambertian shade of the bed lit from the north-west, 0 (dark) to 1."""
    gy, gx = np.gradient(np.where(np.isfinite(bed), bed, np.nanmean(bed)), dx)
    slope = np.pi / 2 - np.arctan(np.hypot(gx, gy))
    aspect = np.arctan2(-gx, gy)
    azimuth, altitude = np.radians(315.0), np.radians(45.0)
    return np.clip(np.sin(altitude) * np.sin(slope) +
                   np.cos(altitude) * np.cos(slope) * np.cos(azimuth - aspect), 0, 1)


def source_index(ds, name):
    names = [str(n) for n in ds["source_name"][:]]
    if name not in names:
        sys.exit(f"no source '{name}' in the file; its sources: {', '.join(names)}")
    return names.index(name)


def axes_km(ds):
    x, y = ds["x"][:] / 1000.0, ds["y"][:] / 1000.0
    dx, dy = float(x[1] - x[0]), float(y[1] - y[0])
    return [x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2]


def draw_map(ds, field, title, label, cmap, vmax, out):
    extent = axes_km(ds)
    # As tall as the domain is for its width: a flume is a strip, a valley a square.
    aspect = (extent[3] - extent[2]) / (extent[1] - extent[0])
    fig, ax = plt.subplots(figsize=(8.0, max(2.6, 6.8 * aspect) + 0.8))
    if "bed_elevation" in ds.variables:
        dx = float(ds["x"][1] - ds["x"][0])
        bed = np.ma.filled(ds["bed_elevation"][:].astype(float), np.nan)
        ax.imshow(hillshade(bed, dx), origin="lower", extent=extent, cmap="gray", vmin=0,
                  vmax=1.2)
    image = ax.imshow(np.ma.masked_invalid(field), origin="lower", extent=extent, cmap=cmap,
                      vmin=0, vmax=vmax, alpha=0.85)
    fig.colorbar(image, ax=ax, shrink=0.9 if aspect < 0.5 else 0.8, label=label)
    ax.set_xlabel("x (km)")
    ax.set_ylabel("y (km)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def filled(variable):
    return np.ma.filled(variable.astype(float), np.nan)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("--source", help="the source whose share is mapped")
    parser.add_argument("--time", type=float, help="map this output time (s), not the maximum")
    parser.add_argument("--age", action="store_true", help="map the water's mean age")
    parser.add_argument("--gauges", help="write the gauges' shares over time to this file")
    parser.add_argument("--out", default="provenance.png")
    args = parser.parse_args()
    ds = netCDF4.Dataset(args.file)

    if args.gauges:
        times = ds["series_time"][:] / 3600.0
        depth = filled(ds["gauge_depth"][:])
        shares = np.nan_to_num(filled(ds["gauge_source_share"][:]))
        names = [str(n) for n in ds["gauge_name"][:]]
        sources = [str(n) for n in ds["source_name"][:]]
        fig, axes = plt.subplots(len(names), 1, figsize=(7.5, 2.4 * len(names)), sharex=True)
        for g, ax in enumerate(np.atleast_1d(axes)):
            parts = [np.nan_to_num(depth[:, g]) * shares[:, g, k] for k in range(len(sources))]
            ax.stackplot(times, parts, labels=sources)
            ax.set_ylabel("depth (m)")
            ax.set_title(f"gauge {names[g]}: its water by source", fontsize=10)
        ax.set_xlabel("time (h)")
        np.atleast_1d(axes)[0].legend(loc="upper left", fontsize=8)
        fig.tight_layout()
        fig.savefig(args.gauges, dpi=130)
        return

    if args.age:
        if args.time is None:
            field, when = filled(ds["max_mean_age"][:]), "largest over the run"
        else:
            k = int(np.argmin(np.abs(ds["time"][:] - args.time)))
            field, when = filled(ds["mean_age"][k]), f"t = {float(ds['time'][k]) / 3600:.2f} h"
        draw_map(ds, field / 3600.0, f"mean age of the water, {when}", "mean age (h)",
                 "viridis", np.nanmax(field) / 3600.0, args.out)
        return

    if not args.source:
        sys.exit("say which --source to map (or --age, or --gauges)")
    k = source_index(ds, args.source)
    if args.time is None:
        field, when = filled(ds["max_source_share"][k]), "largest share over the run"
    else:
        t = int(np.argmin(np.abs(ds["time"][:] - args.time)))
        field = filled(ds["source_share"][t, k])
        when = f"share at t = {float(ds['time'][t]) / 3600:.2f} h"
    draw_map(ds, field, f"water from '{args.source}': {when}", "share of the cell's water",
             "plasma", 1.0, args.out)


if __name__ == "__main__":
    main()
