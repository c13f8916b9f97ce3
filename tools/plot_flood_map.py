#!/usr/bin/python3
"""Flood maps and volume balance of a swe-mps netCDF file.

Map mode draws one gridded field (max_depth unless --field says otherwise) over a
hillshade of the terrain. Fields with one map per depth threshold (arrival_time,
inundation_duration) take --threshold; the hazard classes (hazard_class_uk,
hazard_class_aidr) are drawn as classes with a legend. The terrain is the file's bed_elevation, or a GeoTIFF given with
--dem (read through Pillow, which matplotlib already needs). Cells are coloured only where
the water exceeded the run's wet threshold, so dry land shows as relief. Axes are in km of
the file's coordinates (in m for domains under 1 km, such as flumes), and the title names
the CRS when the file has one.

Balance mode (--balance) plots the volume in the domain and the cumulative inflow and
outflow against time, and the relative volume error on a log axis below.

    /usr/bin/python3 tools/plot_flood_map.py run.nc --out max_depth.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --field arrival_time --threshold 0.3 \
        --out arrival.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --field hazard_class_aidr --out h.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --field depth --time 600 --out d600.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --dem dem.tif --out max_depth.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --balance balance.png
    /usr/bin/python3 tools/plot_flood_map.py run.nc --buildings houses.geojson --out m.png
"""
import argparse
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402

# Colour maps by field; the rest use viridis.
COLORMAPS = {
    "depth": "Blues",
    "max_depth": "Blues",
    "max_speed": "inferno_r",
    "max_depth_speed": "magma_r",
    "max_depth_speed2": "magma_r",
    "max_hazard_rating": "magma_r",
    "max_surface_elevation": "Blues",
    "arrival_time": "viridis_r",  # early arrival stands out
    "time_of_max_depth": "viridis_r",
    "inundation_duration": "viridis",
    "u": "RdBu_r",
    "v": "RdBu_r",
}
# Fields shown everywhere rather than only where the water was deeper than the threshold.
UNMASKED = {"bed_elevation"}

# GeoTIFF tags (GeoTIFF 1.0 spec, section 2.6) and the GDAL no-data tag.
TAG_PIXEL_SCALE = 33550
TAG_TIEPOINT = 33922
TAG_GEOKEYS = 34735
TAG_GDAL_NODATA = 42113
GEOKEY_MODEL_TYPE = 1024
MODEL_GEOGRAPHIC = 2
GEOKEY_RASTER_TYPE = 1025
RASTER_PIXEL_IS_POINT = 2


def crs_name(ds):
    """Name of the file's CRS, or None for local coordinates."""
    if "crs" not in ds.variables:
        return None
    crs = ds["crs"]
    if "projected_crs_name" in crs.ncattrs():
        return crs.projected_crs_name
    wkt = getattr(crs, "crs_wkt", "")
    match = re.match(r'\s*\w+\["([^"]*)"', wkt)
    return match.group(1) if match else "unnamed CRS"


def time_unit(seconds):
    """Divisor and label that make a time axis readable."""
    if seconds <= 600:
        return 1.0, "s"
    if seconds <= 3 * 3600:
        return 60.0, "min"
    return 3600.0, "h"


def hillshade(z, dx, dy, azimuth_deg=315.0, altitude_deg=45.0, z_factor=1.0):
    """Lambertian shade in [0, 1] of a grid whose rows run along +y (north up) by dy.

    The surface normal is (-dz/dx, -dz/dy, 1); the light comes from `azimuth_deg`
    clockwise from north, `altitude_deg` above the horizon.
    """
    z = np.ma.filled(np.ma.masked_invalid(z).astype(float), np.nan) * z_factor
    dz_dy, dz_dx = np.gradient(z, dy, dx)
    az, alt = np.radians(azimuth_deg), np.radians(altitude_deg)
    light = np.array([np.sin(az) * np.cos(alt), np.cos(az) * np.cos(alt), np.sin(alt)])
    norm = np.sqrt(dz_dx**2 + dz_dy**2 + 1.0)
    shade = (-dz_dx * light[0] - dz_dy * light[1] + light[2]) / norm
    return np.ma.masked_invalid(np.clip(shade, 0.0, 1.0))


def read_geotiff(path):
    """Elevation, extent (left, right, bottom, top) and cell size of a north-up GeoTIFF."""
    from PIL import Image  # installed with matplotlib

    try:
        image = Image.open(path)
        z = np.asarray(image, dtype=float)
    except Exception as error:  # Pillow raises several unrelated types
        sys.exit(f"cannot read {path} as a single-band GeoTIFF: {error}")
    tags = image.tag_v2
    if TAG_PIXEL_SCALE not in tags or TAG_TIEPOINT not in tags:
        sys.exit(f"{path} has no GeoTIFF georeferencing (pixel scale and tie point)")
    sx, sy = tags[TAG_PIXEL_SCALE][:2]
    col, row, _, x, y, _ = tags[TAG_TIEPOINT][:6]
    keys = tags.get(TAG_GEOKEYS, ())
    # Entries of four shorts (id, location, count, value) after a four-short header.
    for k in range(4, len(keys) - 3, 4):
        if keys[k] == GEOKEY_RASTER_TYPE and keys[k + 3] == RASTER_PIXEL_IS_POINT:
            col, row = col - 0.5, row - 0.5  # the tie point is a cell centre
        if keys[k] == GEOKEY_MODEL_TYPE and keys[k + 3] == MODEL_GEOGRAPHIC:
            sys.exit(f"{path} is in degrees; reproject it to the file's CRS first "
                     "(gdalwarp -t_srs)")
    left, top = x - col * sx, y + row * sy
    nodata = tags.get(TAG_GDAL_NODATA)
    if nodata is not None:
        z = np.where(z == float(str(nodata).strip("\x00 ")), np.nan, z)
    nrows, ncols = z.shape
    extent = (left, left + ncols * sx, top - nrows * sy, top)
    # Rows run from the top; flip them so that they run along +y like the netCDF grid.
    return z[::-1, :], extent, sx, sy


def grid_extent(x, y):
    """Cell-edge extent (left, right, bottom, top) of cell-centre coordinates."""
    dx = float(x[1] - x[0]) if len(x) > 1 else 1.0
    dy = float(y[1] - y[0]) if len(y) > 1 else 1.0
    return (x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2), dx, dy


def read_field(ds, name, time, threshold=None):
    """The field as a masked (y, x) array, and a label for the time or threshold it shows."""
    if name not in ds.variables:
        gridded = [v for v in ds.variables if ds[v].dimensions[-2:] == ("y", "x")]
        sys.exit(f"no variable '{name}' in the file; gridded ones: {', '.join(gridded)}")
    var = ds[name]
    if var.dimensions == ("y", "x"):
        return var[:, :], None
    if var.dimensions == ("depth_threshold", "y", "x"):
        thresholds = ds["depth_threshold"][:]
        if threshold is None:
            k = 0  # the wet depth
        else:
            k = int(np.argmin(np.abs(thresholds - threshold)))
            if abs(float(thresholds[k]) - threshold) > 1e-9:
                listed = ", ".join(f"{float(t):g}" for t in thresholds)
                sys.exit(f"'{name}' has no map for {threshold:g} m; its thresholds: {listed} m")
        return var[k, :, :], f"depth > {float(thresholds[k]):g} m"
    if var.dimensions != ("time", "y", "x"):
        sys.exit(f"'{name}' is not a map (its dimensions are {var.dimensions})")
    times = ds["time"][:]
    if len(times) == 0:
        sys.exit("the file has no output times")
    k = int(np.argmin(np.abs(times - time))) if time is not None else len(times) - 1
    return var[k, :, :], f"t = {float(times[k]):g} s"


def wet_mask(ds, name, field, time):
    """Cells to leave uncoloured: those never (or, for a time slice, not then) wet."""
    if name in UNMASKED:
        return np.zeros(field.shape, dtype=bool)
    if ds[name].dimensions[0] == "time" and "depth" in ds.variables:
        depth, _ = read_field(ds, "depth", time)
    elif "max_depth" in ds.variables:
        depth = ds["max_depth"][:, :]
    else:
        return np.zeros(field.shape, dtype=bool)
    threshold = 0.0
    if "max_depth" in ds.variables:
        threshold = float(getattr(ds["max_depth"], "wet_depth_threshold_m", 0.0))
    return np.ma.filled(depth <= threshold, True)


def plot_map(args):
    with netCDF4.Dataset(args.file) as ds:
        x, y = ds["x"][:], ds["y"][:]
        extent, dx, dy = grid_extent(x, y)
        field, when = read_field(ds, args.field, args.time, args.threshold)
        field = np.ma.masked_where(wet_mask(ds, args.field, field, args.time), field)
        classes = None
        if "flag_meanings" in ds[args.field].ncattrs():
            classes = (list(ds[args.field].flag_values), ds[args.field].flag_meanings.split())
            field = np.ma.masked_where(np.ma.filled(field, 0) == 0, field)  # not flooded
        # NaN under the mask: matplotlib would otherwise scale the hidden fill values too.
        field = np.ma.masked_invalid(np.ma.filled(field.astype(float), np.nan))
        var = ds[args.field]
        label = f"{getattr(var, 'long_name', args.field)} ({getattr(var, 'units', '?')})"
        crs = crs_name(ds)
        bed = ds["bed_elevation"][:, :] if "bed_elevation" in ds.variables else None
        gauges = None
        if "gauge_name" in ds.variables:
            gauges = (list(ds["gauge_name"][:]), ds["gauge_x"][:], ds["gauge_y"][:])

    # km for real floods; m for laboratory flumes.
    size_m = max(extent[1] - extent[0], extent[3] - extent[2])
    scale, unit = (1e-3, "km") if size_m >= 1000.0 else (1.0, "m")
    fig, ax = plt.subplots(figsize=(args.width, args.width * 0.75))
    if args.dem:
        z, dem_extent, sx, sy = read_geotiff(args.dem)
        shade, shade_extent = hillshade(z, sx, sy, z_factor=args.z_factor), dem_extent
    elif bed is not None:
        shade, shade_extent = hillshade(bed, dx, dy, z_factor=args.z_factor), extent
    else:
        shade = None
        print("no bed_elevation in the file and no --dem: drawing without relief", file=sys.stderr)
    if shade is not None and shade.count() > 0:
        # Stretched to its own range: floodplains are flat, and unstretched relief is grey.
        low, high = np.percentile(shade.compressed(), [1, 99])
        high = max(high, low + 1e-3)
        ax.imshow(shade, cmap="gray", vmin=low - 0.5 * (high - low), vmax=high, origin="lower",
                  extent=[e * scale for e in shade_extent], interpolation="nearest")

    cmap = COLORMAPS.get(args.field, "viridis")
    if field.count() == 0:
        print(f"'{args.field}' has no wet cells to draw", file=sys.stderr)
    norm = None
    if cmap == "RdBu_r" and field.count() > 0:
        limit = float(np.abs(field).max()) or 1.0
        norm = matplotlib.colors.Normalize(-limit, limit)
    if classes is not None:
        # One colour a class, light to dark as the hazard rises; never-flooded cells show relief.
        values, names = [v for v in classes[0] if v > 0], classes[1][1:]
        colours = plt.get_cmap("YlOrRd")(np.linspace(0.1, 0.95, len(values)))
        cmap = matplotlib.colors.ListedColormap(colours)
        norm = matplotlib.colors.BoundaryNorm(np.arange(len(values) + 1) + 0.5, len(values))
        ax.imshow(field, cmap=cmap, norm=norm, origin="lower", alpha=args.alpha,
                  extent=[e * scale for e in extent], interpolation="nearest")
        handles = [matplotlib.patches.Patch(color=c, label=n.replace("_", " "))
                   for c, n in zip(colours, names)]
        title = label.rsplit(" (", 1)[0]  # classes have no unit
        ax.legend(handles=handles, loc="lower right", fontsize=8, title=title, title_fontsize=8)
    else:
        image = ax.imshow(field, cmap=cmap, norm=norm, origin="lower", alpha=args.alpha,
                          extent=[e * scale for e in extent], interpolation="nearest")
        fig.colorbar(image, ax=ax, shrink=0.8, label=label)

    if gauges is not None:
        names, gx, gy = gauges
        ax.plot(gx * scale, gy * scale, "k^", markersize=6, markerfacecolor="white")
        for name, px, py in zip(names, gx, gy):
            ax.annotate(name, (px * scale, py * scale), xytext=(4, 4), textcoords="offset points",
                        fontsize=8)

    if args.buildings:
        for ring in building_rings(args.buildings):
            xs, ys = zip(*ring)
            ax.fill([v * scale for v in xs], [v * scale for v in ys], facecolor="0.35",
                    edgecolor="black", linewidth=0.4)

    ax.set_xlim(extent[0] * scale, extent[1] * scale)
    ax.set_ylim(extent[2] * scale, extent[3] * scale)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x ({unit})" if crs is None else f"easting ({unit})")
    ax.set_ylabel(f"y ({unit})" if crs is None else f"northing ({unit})")
    title = args.field + (f", {when}" if when else "")
    ax.set_title(title + (f"\n{crs}" if crs else ""), fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=args.dpi)
    print(f"wrote {args.out}")


def plot_balance(args):
    with netCDF4.Dataset(args.file) as ds:
        if "series_time" not in ds.variables:
            sys.exit("the file has no volume-balance series (no series_time)")
        t = np.ma.filled(ds["series_time"][:].astype(float), np.nan)
        series = {name: np.ma.filled(ds[name][:].astype(float), np.nan)
                  for name in ("volume_in_domain", "volume_inflow", "volume_outflow",
                               "volume_error")}
        crs = crs_name(ds)
    if len(t) == 0:
        sys.exit("the volume-balance series is empty")
    scale, unit = time_unit(float(np.nanmax(t)))
    ts = t / scale

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(args.width, args.width * 0.7), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 2]})
    top.plot(ts, series["volume_in_domain"], "k-", label="in domain")
    top.plot(ts, series["volume_inflow"], "b--", label="inflow (cumulative)")
    top.plot(ts, series["volume_outflow"], "r--", label="outflow (cumulative)")
    top.set_ylabel("volume (m³)")
    top.legend(fontsize=8)
    top.grid(alpha=0.3)
    top.set_title("volume balance" + (f"\n{crs}" if crs else ""), fontsize=10)

    # A log axis shows |error|; the sign is kept by the marker colour.
    error = series["volume_error"]
    shown = np.isfinite(error) & (error != 0.0)
    bottom.semilogy(ts[shown], np.abs(error[shown]), "-", color="0.6", linewidth=0.8)
    positive = shown & (error > 0)
    negative = shown & (error < 0)
    bottom.semilogy(ts[positive], error[positive], "o", color="tab:red", markersize=3,
                    label="gain (> 0)")
    bottom.semilogy(ts[negative], -error[negative], "o", color="tab:blue", markersize=3,
                    label="loss (< 0)")
    if shown.any():
        bottom.legend(fontsize=8)
    else:
        bottom.text(0.5, 0.5, "relative error is zero throughout", transform=bottom.transAxes,
                    ha="center")
    bottom.set_ylabel("|relative volume error|")
    bottom.set_xlabel(f"time ({unit})")
    bottom.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(args.balance, dpi=args.dpi)
    print(f"wrote {args.balance}")


def building_rings(path):
    """The outer rings of a GeoJSON file's polygons and multipolygons, in its coordinates."""
    import json
    with open(path) as f:
        collection = json.load(f)
    rings = []
    for feature in collection.get("features", []):
        geometry = feature.get("geometry") or {}
        if geometry.get("type") == "Polygon":
            rings.append(geometry["coordinates"][0])
        elif geometry.get("type") == "MultiPolygon":
            rings.extend(polygon[0] for polygon in geometry["coordinates"])
    return rings


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file", help="netCDF file written by swe-mps run")
    ap.add_argument("--field", default="max_depth",
                    help="gridded variable to draw (default max_depth)")
    ap.add_argument("--time", type=float,
                    help="for a per-time field, the output time in s (default: the last)")
    ap.add_argument("--threshold", type=float,
                    help="for a field per depth threshold (arrival_time, inundation_duration), "
                         "the threshold in m (default: the wet depth)")
    ap.add_argument("--dem", help="GeoTIFF of the terrain for the hillshade "
                                  "(default: the file's bed_elevation)")
    ap.add_argument("--out", help="PNG of the map (default flood_map.png without --balance)")
    ap.add_argument("--balance", metavar="PNG", help="PNG of the volume balance")
    ap.add_argument("--z-factor", type=float, default=1.0,
                    help="vertical exaggeration of the hillshade (default 1)")
    ap.add_argument("--alpha", type=float, default=0.85,
                    help="opacity of the field over the relief (default 0.85)")
    ap.add_argument("--width", type=float, default=8.0, help="figure width in inches")
    ap.add_argument("--dpi", type=int, default=150)
    ap.add_argument("--buildings", help="GeoJSON file of building footprints to draw, in the "
                    "file's coordinates")
    args = ap.parse_args()
    if args.out is None and args.balance is None:
        args.out = "flood_map.png"
    if args.out:
        plot_map(args)
    if args.balance:
        plot_balance(args)


if __name__ == "__main__":
    main()
