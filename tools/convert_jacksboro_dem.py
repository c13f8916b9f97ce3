#!/usr/bin/python3
"""Turn matplotlib's Jacksboro fault sample DEM into a longitude/latitude GeoTIFF.

The source, jacksboro_fault_dem.npz in matplotlib's sample data, is a 3 arc-second USGS DEM
of Campbell County, Tennessee, and the Kentucky line north of it: an int16 array `elevation`
(344 rows x 403 columns, metres) with scalars xmin, xmax, ymin, ymax and dx, dy in degrees.
It records no CRS and no nodata value. What this script reads into it:

- Bounds are outer cell edges, not centres: (xmax - xmin) / dx is exactly 403 and
  |ymax - ymin| / dy exactly 344, the array's shape (edges at odd multiples of 1.5", so
  cell centres lie on whole multiples of 3", as in USGS 3" grids). The script checks this.
- "ymin" (36.7329) is larger than "ymax" (36.4463): the two names follow the row order,
  the latitude of the first row's edge and of the last's, not their size. Row 0 is the
  northern row (north-up, as DEM exports usually are), because
  * matplotlib's own examples read it that way: the 3-D surface example spreads the rows
    over linspace(ymin, ymax, nrows), so row 0 sits at 36.7329 N, and the hillshading
    examples draw row 0 at the top with light from the north-west;
  * the terrain agrees only this way round: the Jacksboro fault then runs north-west,
    with the Pine Mountain ridge leaving it toward the north-east, as both are mapped (a
    north-west tear fault at the south-west end of the Pine Mountain thrust block, in
    ridges that strike north-east). Flipped, the Appalachian ridge would strike north-west.
  So the raster's top edge is max(ymin, ymax) and its rows are written as stored.
- The datum is not recorded. USGS DEMs of this kind are NAD83 horizontally (and NAVD88
  metres vertically); the file is labelled WGS 84 (EPSG:4326), from which NAD83 differs by
  about a metre here, far below the ~75 x 93 m cells.

The output is float32 (the int16 metres are exact in it), deflate-compressed, with NaN
declared as nodata: the source has no gaps, but a warp to a projected CRS then marks the
corners outside the footprint as NaN instead of 0 m. Scenes use it through `bed.crs`, e.g.
UTM zone 16N (EPSG:32616), which holds the whole raster.

    /usr/bin/python3 tools/convert_jacksboro_dem.py
    /usr/bin/python3 tools/convert_jacksboro_dem.py --source dem.npz --output dem.tif
"""
import argparse
import pathlib

import numpy as np
from osgeo import gdal, osr

gdal.UseExceptions()

REPO = pathlib.Path(__file__).resolve().parent.parent
DEFAULT_SOURCE = pathlib.Path("/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz")
DEFAULT_OUTPUT = REPO / "data" / "jacksboro_fault_dem.tif"


def read_source(path):
    with np.load(path) as npz:
        elevation = npz["elevation"]
        bounds = {k: float(npz[k]) for k in ("xmin", "xmax", "ymin", "ymax", "dx", "dy")}
    rows, columns = elevation.shape
    width = abs(bounds["xmax"] - bounds["xmin"]) / bounds["dx"]
    height = abs(bounds["ymax"] - bounds["ymin"]) / bounds["dy"]
    # Bounds that are outer edges span exactly the array; centres would span one cell less.
    if not (np.isclose(width, columns, atol=1e-6) and np.isclose(height, rows, atol=1e-6)):
        raise SystemExit(
            f"{path}: bounds span {width:.3f} x {height:.3f} cells but the array is "
            f"{columns} x {rows}; the layout this script assumes does not hold"
        )
    return elevation, bounds


def write_geotiff(elevation, bounds, path):
    rows, columns = elevation.shape
    values = elevation.astype(np.float32)
    # Large negative int16 values are the usual gap markers; this DEM has none.
    values[elevation <= -32767] = np.nan
    west = min(bounds["xmin"], bounds["xmax"])
    north = max(bounds["ymin"], bounds["ymax"])  # row 0 is the northern row (see above)
    path.parent.mkdir(parents=True, exist_ok=True)
    driver = gdal.GetDriverByName("GTiff")
    dataset = driver.Create(
        str(path), columns, rows, 1, gdal.GDT_Float32,
        options=["COMPRESS=DEFLATE", "PREDICTOR=3", "ZLEVEL=9"],
    )
    dataset.SetGeoTransform((west, bounds["dx"], 0.0, north, 0.0, -bounds["dy"]))
    crs = osr.SpatialReference()
    crs.ImportFromEPSG(4326)
    dataset.SetSpatialRef(crs)
    dataset.SetMetadataItem("SOURCE", "USGS 3 arc-second DEM, matplotlib sample data "
                            "jacksboro_fault_dem.npz")
    band = dataset.GetRasterBand(1)
    band.SetDescription("elevation")
    band.SetUnitType("m")
    band.SetNoDataValue(float("nan"))
    band.WriteArray(values)
    band.ComputeStatistics(False)
    dataset = None  # closing writes the file
    return values, (west, west + columns * bounds["dx"], north - rows * bounds["dy"], north)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", type=pathlib.Path, default=DEFAULT_SOURCE,
                        help="matplotlib's jacksboro_fault_dem.npz (default: %(default)s)")
    parser.add_argument("--output", type=pathlib.Path, default=DEFAULT_OUTPUT,
                        help="GeoTIFF to write (default: %(default)s)")
    args = parser.parse_args()
    elevation, bounds = read_source(args.source)
    values, (west, east, south, north) = write_geotiff(elevation, bounds, args.output)
    rows, columns = values.shape
    gaps = int(np.isnan(values).sum())
    print(f"wrote {args.output} ({args.output.stat().st_size} bytes)")
    print(f"  size      {columns} columns x {rows} rows, cells {bounds['dx'] * 3600:.2f}\" x "
          f"{bounds['dy'] * 3600:.2f}\", EPSG:4326")
    print(f"  longitude {west:.6f} to {east:.6f}")
    print(f"  latitude  {south:.6f} to {north:.6f}")
    print(f"  elevation {np.nanmin(values):.0f} to {np.nanmax(values):.0f} m, {gaps} nodata cells")


if __name__ == "__main__":
    main()
