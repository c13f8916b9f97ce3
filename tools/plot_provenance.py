#!/usr/bin/python3
"""Where the water came from, from a swe-mps netCDF file written with output.provenance.

Map mode draws one source's share of each cell's water (max_source_share over the run, or
source_share at --time) over a hillshade of the file's bed_elevation; cells that were never wet
show the relief. Gauge mode (--gauges) draws, for each gauge, the depth at the gauge split into
the sources' shares of it over time (stacked), and the mean-age map is drawn with --age.
Pathline mode (--pathlines) draws the tracks of the particles a run followed (its
NAME_pathlines.gpkg or .geojson), coloured by time, over the run's maximum depth.

    /usr/bin/python3 tools/plot_provenance.py run.nc --source "upper lake" --out share.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --source river --time 7200 --out s.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --gauges gauges.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --age --out age.png
    /usr/bin/python3 tools/plot_provenance.py run.nc --pathlines run_pathlines.gpkg --out p.png
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


def draw_relief(ds, ax, extent):
    """The hillshade of the file's bed_elevation, where it has one."""
    if "bed_elevation" in ds.variables:
        dx = float(ds["x"][1] - ds["x"][0])
        bed = np.ma.filled(ds["bed_elevation"][:].astype(float), np.nan)
        ax.imshow(hillshade(bed, dx), origin="lower", extent=extent, cmap="gray", vmin=0,
                  vmax=1.2)


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
    draw_relief(ds, ax, extent)
    image = ax.imshow(np.ma.masked_invalid(field), origin="lower", extent=extent, cmap=cmap,
                      vmin=0, vmax=vmax, alpha=0.85)
    fig.colorbar(image, ax=ax, shrink=0.9 if aspect < 0.5 else 0.8, label=label)
    ax.set_xlabel("x (km)")
    ax.set_ylabel("y (km)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def read_pathlines(path):
    """Each line's vertices as arrays x, y (m) and t (s): M in a GeoPackage, time_s in GeoJSON."""
    from osgeo import ogr  # python3-gdal

    ogr.UseExceptions()
    source = ogr.Open(path)
    if source is None:
        sys.exit(f"cannot open the pathlines '{path}'")
    lines = []
    for feature in source.GetLayer(0):
        geometry = feature.GetGeometryRef()
        n = geometry.GetPointCount()
        x = np.array([geometry.GetX(k) for k in range(n)])
        y = np.array([geometry.GetY(k) for k in range(n)])
        if feature.GetFieldIndex("time_s") >= 0:
            t = np.array(feature.GetFieldAsDoubleList("time_s"))
        else:
            t = np.array([geometry.GetM(k) for k in range(n)])
        lines.append((x, y, t, feature.GetField("fate")))
    return lines


def draw_pathlines(ds, path, out):
    from matplotlib.collections import LineCollection

    lines = read_pathlines(path)
    if not lines:
        sys.exit(f"the pathlines '{path}' hold no line")
    extent = axes_km(ds)
    aspect = (extent[3] - extent[2]) / (extent[1] - extent[0])
    fig, ax = plt.subplots(figsize=(8.0, max(2.6, 6.8 * aspect) + 0.8))
    draw_relief(ds, ax, extent)
    # The water's largest reach over the run, pale, for where the lines could go.
    wet = filled(ds["max_depth"][:])
    threshold = float(getattr(ds["max_depth"], "wet_depth_threshold_m", 0.0))
    ax.imshow(np.ma.masked_where(~(wet > threshold), np.ones_like(wet)), origin="lower",
              extent=extent, cmap="Blues", vmin=0, vmax=3, alpha=0.5)
    t_max = max(float(t.max()) for _, _, t, _ in lines) / 3600.0
    t_min = min(float(t.min()) for _, _, t, _ in lines) / 3600.0
    for x, y, t, _ in lines:
        points = np.column_stack([x / 1000.0, y / 1000.0])
        segments = np.stack([points[:-1], points[1:]], axis=1)
        collection = LineCollection(segments, cmap="viridis", linewidths=1.0)
        collection.set_array(0.5 * (t[:-1] + t[1:]) / 3600.0)
        collection.set_clim(t_min, t_max)
        ax.add_collection(collection)
    ax.plot([x[0] / 1000.0 for x, _, _, _ in lines], [y[0] / 1000.0 for _, y, _, _ in lines],
            "o", ms=2.5, color="white", mec="black", mew=0.4, label="where each was chosen")
    fig.colorbar(collection, ax=ax, shrink=0.8, label="time (h)")
    # Round the lines, a quarter of their extent aside: a spill's tracks are a small part of a
    # valley.
    xs = np.concatenate([x for x, _, _, _ in lines]) / 1000.0
    ys = np.concatenate([y for _, y, _, _ in lines]) / 1000.0
    pad = 0.25 * max(np.ptp(xs), np.ptp(ys), 0.01)
    ax.set_xlim(max(extent[0], xs.min() - pad), min(extent[1], xs.max() + pad))
    ax.set_ylim(max(extent[2], ys.min() - pad), min(extent[3], ys.max() + pad))
    ax.set_xlabel("x (km)")
    ax.set_ylabel("y (km)")
    merged = sum(1 for *_, fate in lines if fate == "merged")
    left = sum(1 for *_, fate in lines if fate == "left the domain")
    ax.set_title(f"{len(lines)} pathlines over the water's reach ({merged} merged into another, "
                 f"{left} left the domain)", fontsize=10)
    ax.legend(loc="lower left", fontsize=8)
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
    parser.add_argument("--pathlines", help="draw the pathlines of this GeoPackage or GeoJSON")
    parser.add_argument("--out", default="provenance.png")
    args = parser.parse_args()
    ds = netCDF4.Dataset(args.file)

    if args.pathlines:
        draw_pathlines(ds, args.pathlines, args.out)
        return

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
